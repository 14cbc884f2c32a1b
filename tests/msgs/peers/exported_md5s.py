"""Import every class of a generated package as rospy would; print {type: md5sum} as JSON.

argv: PACKAGE (found on PYTHONPATH). Run by Debian's /usr/bin/python3.
"""

import importlib
import json
import os
import sys

package = sys.argv[1]
found = {}
for kind in ("msg", "srv"):
    module = importlib.import_module(f"{package}.{kind}")
    for name in sorted(os.listdir(os.path.dirname(module.__file__))):
        if name.startswith("_") and name.endswith(".py") and name != "__init__.py":
            cls = getattr(module, name[1:-3])
            found[cls._type] = cls._md5sum
print(json.dumps(found))
