"""rospy service client: service_client.py NAME SPEC_JSON --fields JSON [--count N]
[--persistent]; prints each response (or the error) as a JSON line."""

import argparse
import json

import rospy
from rospeer import emit, fill, service_class, to_plain

parser = argparse.ArgumentParser()
parser.add_argument("service")
parser.add_argument("spec")
parser.add_argument("--fields", default="{}")
parser.add_argument("--count", type=int, default=1)
parser.add_argument("--persistent", action="store_true")
args = parser.parse_args(rospy.myargv()[1:])
cls = service_class(args.spec)

rospy.init_node("service_client", anonymous=True)
rospy.wait_for_service(args.service, timeout=30)
proxy = rospy.ServiceProxy(args.service, cls, persistent=args.persistent)
for _ in range(args.count):
    request = fill(cls._request_class(), json.loads(args.fields))
    try:
        emit(response=to_plain(proxy.call(request)))
    except rospy.ServiceException as exc:
        emit(error=str(exc))
proxy.close()
