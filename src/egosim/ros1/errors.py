"""Exceptions raised by the ROS 1 transport."""


class Ros1Error(Exception):
    """Base of every error raised by egosim.ros1."""


class InvalidNameError(Ros1Error, ValueError):
    """A graph resource name breaks the ROS naming rules."""


class MasterError(Ros1Error):
    """The master answered a call with a failure or error status code."""


class PeerUnreachableError(Ros1Error):
    """Nothing answers at a peer's XML-RPC or TCPROS address (refused, reset, timed out)."""


class MasterUnreachableError(MasterError, PeerUnreachableError):
    """Nothing answers XML-RPC at the master URI."""


class MulticallUnsupportedError(MasterError):
    """The master does not serve system.multicall (calls then go one by one)."""


class ProtocolError(Ros1Error):
    """A peer sent bytes that break TCPROS framing or the connection header format."""


class FrameTooLargeError(ProtocolError):
    """A length prefix exceeds the configured limit."""


class ConnectionClosedError(ProtocolError):
    """The peer closed the connection, possibly in the middle of a frame."""

    def __init__(self, message: str, mid_frame: bool = False) -> None:
        super().__init__(message)
        self.mid_frame = mid_frame
        """True when part of a frame had arrived: the peer broke off, it did not just leave."""


class ConnectionRefusedByPeerError(Ros1Error):
    """A connection was refused with a reason: an ``error`` header, or a negotiation refusal."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


class ServiceError(Ros1Error):
    """A service call failed: lookup, transport, or the server's handler reported an error."""


class BadRequestError(ServiceError):
    """A service request its handler cannot take (undecodable, or invalid as a whole):
    answered with an error and logged without a traceback."""


class NodeShutdownError(Ros1Error):
    """The node has been shut down (or is shutting down: a service handler may raise it
    for a request that comes too late, which is answered with an error and no traceback)."""
