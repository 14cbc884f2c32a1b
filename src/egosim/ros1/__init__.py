"""egosim.ros1: the ROS 1 wire protocol in pure Python (master and slave XML-RPC APIs,
parameter server, TCPROS topics and services). It moves serialized bytes; message types are
described by name, md5sum and definition.

Public API::

    Node(name, argv=None, *, namespace=None, master_uri=None, host=None, bind_host=None,
         embedded_master="auto", limits=None, rosout_logger="egosim", env=None)
      .advertise(topic, msg_type, *, latch=False, queue_size=100, negotiate=None) -> Publisher
      .subscribe(topic, msg_type, callback, *, tcp_nodelay=False) -> Subscriber
      .advertise_service(service, srv_type, handler, *, negotiate=None) -> ServiceServer
      .service_proxy(service, srv_type, *, persistent=False) -> ServiceProxy
      .get_param / set_param / has_param / delete_param / search_param / get_param_names
      .subscribe_param(key, callback), .resolve_name(name)
      .on_shutdown(callback), .on_shutdown_request(handler), .shutdown(reason),
      .wait_for_shutdown(timeout), .is_shutdown
    Publisher.publish(data), .publish_variants(md5 -> bytes | callable),
        .publish_many([data | variants, ...]), .close()
    Master(uri).start() / .shutdown()    the embedded master
    MasterClient(master_uri, caller_id)  the Master and Parameter Server APIs
"""

from .errors import (
    BadRequestError,
    ConnectionClosedError,
    ConnectionRefusedByPeerError,
    FrameTooLargeError,
    InvalidNameError,
    MasterError,
    MasterUnreachableError,
    NodeShutdownError,
    PeerUnreachableError,
    ProtocolError,
    Ros1Error,
    ServiceError,
)
from .master import Master
from .master_client import MasterClient
from .node import Node
from .publication import Negotiator, Publisher, Variants
from .service import ServiceHandler, ServiceNegotiator, ServiceProxy, ServiceServer
from .subscription import MessageCallback, Subscriber
from .tcpros import Limits
from .types import ANY_TYPE, MessageTypeInfo, ServiceType, ServiceTypeInfo, TopicType

__all__ = [
    "ANY_TYPE",
    "BadRequestError",
    "ConnectionClosedError",
    "ConnectionRefusedByPeerError",
    "FrameTooLargeError",
    "InvalidNameError",
    "Limits",
    "Master",
    "MasterClient",
    "MasterError",
    "MasterUnreachableError",
    "MessageCallback",
    "MessageTypeInfo",
    "Negotiator",
    "Node",
    "NodeShutdownError",
    "PeerUnreachableError",
    "ProtocolError",
    "Publisher",
    "Ros1Error",
    "ServiceError",
    "ServiceHandler",
    "ServiceNegotiator",
    "ServiceProxy",
    "ServiceServer",
    "ServiceType",
    "ServiceTypeInfo",
    "Subscriber",
    "TopicType",
    "Variants",
]
