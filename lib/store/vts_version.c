/* The library's identity (version) and the names of its status values. */
#include "vts.h"

unsigned vts_version(void)
{
    return VTS_VERSION_NUMBER;
}

const char *vts_version_string(void)
{
#define VTS_STR2(x) #x
#define VTS_STR(x)  VTS_STR2(x)
    return VTS_STR(VTS_VERSION_MAJOR) "." VTS_STR(VTS_VERSION_MINOR) "." VTS_STR(VTS_VERSION_PATCH);
#undef VTS_STR
#undef VTS_STR2
}

const char *vts_status_name(int status)
{
    switch (status) {
    case VTS_OK:
        return "ok";
    case VTS_ERR_IO:
        return "io";
    case VTS_ERR_NOMEM:
        return "nomem";
    case VTS_ERR_NOT_VTS:
        return "not-vts";
    case VTS_ERR_VERSION:
        return "version";
    case VTS_ERR_CORRUPT:
        return "corrupt";
    case VTS_ERR_CHECKSUM:
        return "checksum";
    case VTS_ERR_RANGE:
        return "range";
    case VTS_ERR_LIMIT:
        return "limit";
    case VTS_ERR_UNSUPPORTED:
        return "unsupported";
    case VTS_ERR_ARG:
        return "arg";
    case VTS_ERR_CANCELLED:
        return "cancelled";
    case VTS_ERR_BAD_INPUT:
        return "bad-input";
    default:
        return "unknown";
    }
}
