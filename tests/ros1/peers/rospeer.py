"""Helpers shared by the rospy peer scripts (run by Debian's /usr/bin/python3, not the venv)."""

import json
import sys

import genpy
import genpy.dynamic
import genpy.message
import roslib.message
import rospy


def message_class(type_name, definition_path=None):
    """The real Debian class, or one generated from a full definition text (morai_msgs)."""
    if type_name == "*":
        return rospy.AnyMsg
    if definition_path:
        with open(definition_path) as f:
            return genpy.dynamic.generate_dynamic(type_name, f.read())[type_name]
    cls = roslib.message.get_message_class(type_name)
    if cls is None:
        sys.exit(f"unknown message type {type_name}")
    return cls


def service_class(spec_path):
    """A rospy service class from a JSON spec: name, md5sum, request/response name+definition."""
    with open(spec_path) as f:
        spec = json.load(f)
    parts = {}
    for part in ("request", "response"):
        name = spec[part]["name"]
        parts[part] = genpy.dynamic.generate_dynamic(name, spec[part]["definition"])[name]
    return type(
        "DynamicService",
        (),
        {
            "_type": spec["name"],
            "_md5sum": spec["md5sum"],
            "_request_class": parts["request"],
            "_response_class": parts["response"],
        },
    )


def fill(message, fields):
    genpy.message.fill_message_args(message, [fields])
    return message


def to_plain(value):
    if isinstance(value, genpy.TVal):
        return {"secs": value.secs, "nsecs": value.nsecs}
    if isinstance(value, genpy.Message):
        return {slot: to_plain(getattr(value, slot)) for slot in value.__slots__}
    if isinstance(value, (list, tuple)):
        return [to_plain(item) for item in value]
    if isinstance(value, bytes):
        return list(value)
    return value


def emit(**fields):
    print(json.dumps(fields), flush=True)
