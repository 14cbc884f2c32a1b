"""morai_msgs and the ROS standard types: lookup, construction, ROS 1 bytes, md5, definitions.

profile = get_profile("26.r1")
ctrl = profile.message("morai_msgs/CtrlCmd")
data = ctrl.serialize(ctrl.new(longlCmdType=1, accel=0.5))  # a wrong field: a type error
ctrl.md5sum, ctrl.definition           # as sent in a TCPROS connection header
profile.service("morai_msgs/MoraiEventCmdSrv").request
"""

from .definitions import DEFAULT_PROFILE, PROFILES
from .errors import (
    DefinitionError,
    ExportError,
    MsgsError,
    SerializationError,
    UnknownProfileError,
    UnknownTypeError,
)
from .message_type import MessageType, ServiceType, TypedMessageType
from .profile import Profile, get_profile
from .values import FieldValue, Message

__all__ = [
    "DEFAULT_PROFILE",
    "PROFILES",
    "DefinitionError",
    "ExportError",
    "FieldValue",
    "Message",
    "MessageType",
    "MsgsError",
    "Profile",
    "SerializationError",
    "ServiceType",
    "TypedMessageType",
    "UnknownProfileError",
    "UnknownTypeError",
    "get_profile",
]
