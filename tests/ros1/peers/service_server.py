"""rospy service whose response copies the request's field REQ into the response's field RESP:
service_server.py NAME SPEC_JSON --echo REQ:RESP [--fail]."""

import argparse

import rospy
from rospeer import emit, service_class

parser = argparse.ArgumentParser()
parser.add_argument("service")
parser.add_argument("spec")
parser.add_argument("--echo", default="request:response")
parser.add_argument("--fail", action="store_true")
args = parser.parse_args(rospy.myargv()[1:])
source, target = args.echo.split(":")
cls = service_class(args.spec)


def handle(request):
    if args.fail:
        raise rospy.ServiceException("deliberate failure")
    response = cls._response_class()
    setattr(response, target, getattr(request, source))
    emit(event="handled", caller=request._connection_header["callerid"])
    return response


rospy.init_node("service_server")
rospy.Service(args.service, cls, handle)
emit(event="ready")
rospy.spin()
