"""Generate Python message packages the way catkin does (genpy), run by /usr/bin/python3.

Gives tests what a MORAI SIM user has after `catkin_make`: `from morai_msgs.msg import
CtrlCmd` works, with classes generated from .msg/.srv files by Debian's genpy.

argv: OUTDIR MORAI_MSGS_DIR   (MORAI_MSGS_DIR holds msg/ and srv/)
geometry_msgs and sensor_msgs are generated from Debian's /usr/share/<pkg>/msg too,
since Debian ships only their C++ headers.
"""

import os
import sys

import genmsg.command_line
from genpy.generate_initpy import write_modules
from genpy.generator import MsgGenerator, SrvGenerator

outdir, morai_dir = sys.argv[1], sys.argv[2]
share = "/usr/share"
include = {
    "morai_msgs": [os.path.join(morai_dir, "msg")],
    "std_msgs": [os.path.join(share, "std_msgs", "msg")],
    "geometry_msgs": [os.path.join(share, "geometry_msgs", "msg")],
    "sensor_msgs": [os.path.join(share, "sensor_msgs", "msg")],
}
search_path = genmsg.command_line.includepath_to_dict(
    [f"{package}:{paths[0]}" for package, paths in include.items()]
)


def generate(package, kind, generator, source_dir):
    files = sorted(
        os.path.join(source_dir, name)
        for name in os.listdir(source_dir)
        if name.endswith("." + kind)
    )
    target = os.path.join(outdir, package, kind)
    os.makedirs(target, exist_ok=True)
    code = generator.generate_messages(package, files, target, search_path)
    if code:
        sys.exit(f"genpy failed for {package}/{kind}")
    write_modules(target)


for package in ("geometry_msgs", "sensor_msgs"):
    generate(package, "msg", MsgGenerator(), include[package][0])
generate("morai_msgs", "msg", MsgGenerator(), os.path.join(morai_dir, "msg"))
generate("morai_msgs", "srv", SrvGenerator(), os.path.join(morai_dir, "srv"))
for package in ("geometry_msgs", "sensor_msgs", "morai_msgs"):
    open(os.path.join(outdir, package, "__init__.py"), "w").close()
print("built", outdir)
