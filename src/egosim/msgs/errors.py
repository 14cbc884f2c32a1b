"""Errors of the message layer."""


class MsgsError(Exception):
    """Base class of every message-layer error."""


class UnknownProfileError(MsgsError):
    """The named protocol profile (morai_msgs release) is not shipped."""


class UnknownTypeError(MsgsError):
    """The named message or service type does not exist in the profile."""


class DefinitionError(MsgsError):
    """A shipped .msg/.srv file cannot be parsed."""


class SerializationError(MsgsError):
    """A message could not be turned into bytes, or bytes into a message."""


class ExportError(MsgsError):
    """Message definitions could not be exported (unwritable folder, no genpy)."""
