"""Serialise a message with Debian's genpy from a definition text (run by /usr/bin/python3).

stdin: {"type": "pkg/Name", "definition": full text, "values": nested dict}
stdout: the serialised bytes, hex encoded.
"""

import io
import json
import sys

import genpy
import genpy.dynamic


def assign(message, values):
    for name, value in values.items():
        current = getattr(message, name)
        if isinstance(current, genpy.Time):
            setattr(message, name, genpy.Time(value["secs"], value["nsecs"]))
        elif isinstance(value, dict):
            assign(current, value)
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            item_type = type(message)._slot_types[type(message).__slots__.index(name)][:-2]
            items = []
            for item_values in value:
                item = classes[item_type]()
                assign(item, item_values)
                items.append(item)
            setattr(message, name, items)
        else:
            setattr(message, name, value)


request = json.load(sys.stdin)
classes = genpy.dynamic.generate_dynamic(request["type"], request["definition"])
message = classes[request["type"]]()
assign(message, request["values"])
buffer = io.BytesIO()
message.serialize(buffer)
sys.stdout.write(buffer.getvalue().hex())
