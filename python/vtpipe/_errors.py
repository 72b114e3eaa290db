"""The package's exceptions: libvts's statuses and messages as VtsError and VtsRangeError."""
from . import _lib


class VtsError(Exception):
    """A libvts or libvts-decode failure: str() is the library's message; status is the negative
    enum vts_status value and status_name its stable name ("io", "corrupt", "range"...)."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status
        self.status_name = _lib.vts.vts_status_name(status).decode()


class VtsRangeError(VtsError, IndexError):
    """A layer, level, tile or rectangle the store does not hold (VTS_ERR_RANGE)."""


# named as the package exports them (tracebacks say vtpipe.VtsError, as before this module)
VtsError.__module__ = VtsRangeError.__module__ = "vtpipe"


def raise_error(err):
    """Raises the exception of a filled struct vts_error."""
    cls = VtsRangeError if err.status == _lib.STATUS_RANGE else VtsError
    raise cls(err.status, err.message.decode("utf-8", "replace"))
