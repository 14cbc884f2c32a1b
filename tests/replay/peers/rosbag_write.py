"""Write a bag with Debian's rosbag Python API and genpy classes (run by /usr/bin/python3).

stdin: {"path": bag, "definitions": {"pkg/Name": full text},
        "messages": [{"topic", "type", "receive_ns", "values"}]}
Values are filled the way `rostopic pub` fills them (genpy's fill_message_args),
except message arrays, whose item classes exist only in this dynamic module.
"""

import json
import sys

import genpy
import genpy.dynamic
import genpy.message
import rosbag


def fill(message, values, generated):
    """fill_message_args, building the items of message arrays from `generated` classes."""
    plain = dict(values)
    for name, slot_type in zip(message.__slots__, message._slot_types, strict=True):
        item_type = slot_type[:-2] if slot_type.endswith("[]") else None
        if name in plain and item_type in generated:
            items = []
            for item_values in plain.pop(name):
                item = generated[item_type]()
                fill(item, item_values, generated)
                items.append(item)
            setattr(message, name, items)
    genpy.message.fill_message_args(message, [plain])


request = json.load(sys.stdin)
generated_by_type = {
    type_name: genpy.dynamic.generate_dynamic(type_name, definition)
    for type_name, definition in request["definitions"].items()
}

with rosbag.Bag(request["path"], "w") as bag:
    for item in request["messages"]:
        generated = generated_by_type[item["type"]]
        message = generated[item["type"]]()
        fill(message, item["values"], generated)
        bag.write(item["topic"], message, t=genpy.Time(nsecs=item["receive_ns"]))
