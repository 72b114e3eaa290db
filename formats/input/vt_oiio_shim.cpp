// libvt_oiio.so: the OpenImageIO fallback of formats/input/vt_image_input.c, behind the plain C ABI
// in internal/vt_oiio_abi.h. Built as a module and dlopen()ed by vt_input_oiio.c only when a file
// in a format without a native reader is met, so that the tools never link OpenImageIO. Every
// exception stops here. Streams with ImageInput (read_scanlines / read_tiles), never ImageBuf,
// which would decode the whole image. Alpha is left unassociated, as the native readers leave it.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "internal/vt_oiio_abi.h"
#include "vts.h"

#define VT_OIIO_EXPORT extern "C" __attribute__((visibility("default")))

namespace
{

struct Handle {
    std::unique_ptr<OIIO::ImageInput> in;
    OIIO::ImageSpec spec;
    OIIO::TypeDesc type; // what the caller gets
    size_t texel_bytes = 0;
    std::vector<unsigned char> buffer;
};

void set_error(char *err, const std::string &msg)
{
    std::string line = msg;
    std::replace(line.begin(), line.end(), '\n', ' ');
    std::snprintf(err, VT_OIIO_ERR_MAX, "%s", line.c_str());
}

// The caller's sample type for a stored type: 8/16-bit unsigned and half/float as stored,
// everything else converted to float.
void choose_type(const OIIO::TypeDesc &stored, OIIO::TypeDesc *type, uint32_t *sample)
{
    if (stored == OIIO::TypeDesc::UINT8) {
        *type = OIIO::TypeDesc::UINT8;
        *sample = VTS_SAMPLE_U8;
    } else if (stored == OIIO::TypeDesc::UINT16) {
        *type = OIIO::TypeDesc::UINT16;
        *sample = VTS_SAMPLE_U16;
    } else if (stored == OIIO::TypeDesc::HALF) {
        *type = OIIO::TypeDesc::HALF;
        *sample = VTS_SAMPLE_F16;
    } else {
        *type = OIIO::TypeDesc::FLOAT;
        *sample = VTS_SAMPLE_F32;
    }
}

void *open_file(const char *path, vt_oiio_info *info, int *result, char *err)
{
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path, &config);
    if (!in) {
        std::string msg = OIIO::geterror();
        bool unknown = msg.find("could not find a format reader") != std::string::npos;
        *result = unknown ? VT_OIIO_UNKNOWN_FORMAT : VT_OIIO_BAD_FILE;
        set_error(err, unknown ? "format not recognised" : msg);
        return nullptr;
    }
    std::unique_ptr<Handle> h(new Handle);
    h->spec = in->spec();
    const OIIO::ImageSpec &s = h->spec;
    if (s.nchannels < 1 || s.nchannels > 4 || s.depth > 1 || s.width <= 0 || s.height <= 0) {
        *result = VT_OIIO_UNSUPPORTED;
        set_error(err, std::to_string(s.nchannels) + " channels of " + std::to_string(s.width) +
                           "x" + std::to_string(s.height) + "x" + std::to_string(s.depth) +
                           " texels (1 to 4 channels of a 2D image are supported)");
        return nullptr;
    }
    std::memset(info, 0, sizeof *info);
    info->width = (uint32_t)s.width;
    info->height = (uint32_t)s.height;
    info->channels = (uint32_t)s.nchannels;
    choose_type(s.format, &h->type, &info->sample);
    info->has_alpha = s.nchannels == 2 || s.nchannels == 4;
    info->tile_w = s.tile_width > 0 ? (uint32_t)s.tile_width : 0;
    info->tile_h = s.tile_height > 0 ? (uint32_t)s.tile_height : 0;
    std::snprintf(info->format, sizeof info->format, "%s", in->format_name());
    h->texel_bytes = h->type.size() * (size_t)s.nchannels;
    h->in = std::move(in);
    *result = VT_OIIO_OK;
    return h.release();
}

// Reads rows [y, y + h) of a scanline file, 16 at a time, and crops them.
bool read_scanlines(Handle *h, uint32_t x, uint32_t y, uint32_t w, uint32_t rows,
                    unsigned char *dst, size_t dst_stride)
{
    const OIIO::ImageSpec &s = h->spec;
    size_t row_bytes = h->texel_bytes * (size_t)s.width;
    const uint32_t band = 16;
    h->buffer.resize(row_bytes * band);
    for (uint32_t r = 0; r < rows; r += band) {
        uint32_t n = std::min(band, rows - r);
        int y0 = s.y + (int)(y + r);
        if (!h->in->read_scanlines(0, 0, y0, y0 + (int)n, 0, 0, s.nchannels, h->type,
                                   h->buffer.data()))
            return false;
        for (uint32_t i = 0; i < n; i++)
            std::memcpy(dst + (r + i) * dst_stride,
                        h->buffer.data() + i * row_bytes + x * h->texel_bytes, w * h->texel_bytes);
    }
    return true;
}

// Reads the tiles covering the region (aligned outward) and crops them.
bool read_tiles(Handle *h, uint32_t x, uint32_t y, uint32_t w, uint32_t rows, unsigned char *dst,
                size_t dst_stride)
{
    const OIIO::ImageSpec &s = h->spec;
    uint32_t tw = (uint32_t)s.tile_width, th = (uint32_t)s.tile_height;
    uint32_t ax0 = x / tw * tw, ay0 = y / th * th;
    uint32_t ax1 = std::min((x + w + tw - 1) / tw * tw, (uint32_t)s.width);
    uint32_t ay1 = std::min((y + rows + th - 1) / th * th, (uint32_t)s.height);
    size_t row_bytes = h->texel_bytes * (ax1 - ax0);
    h->buffer.resize(row_bytes * (ay1 - ay0));
    if (!h->in->read_tiles(0, 0, s.x + (int)ax0, s.x + (int)ax1, s.y + (int)ay0, s.y + (int)ay1,
                           s.z, s.z + 1, 0, s.nchannels, h->type, h->buffer.data()))
        return false;
    for (uint32_t r = 0; r < rows; r++)
        std::memcpy(dst + r * dst_stride,
                    h->buffer.data() + (y - ay0 + r) * row_bytes + (x - ax0) * h->texel_bytes,
                    w * h->texel_bytes);
    return true;
}

} // namespace

VT_OIIO_EXPORT int vt_oiio_abi_version(void)
{
    return VT_OIIO_ABI_VERSION;
}

VT_OIIO_EXPORT void *vt_oiio_open(const char *path, vt_oiio_info *info, int *result,
                                  char err[VT_OIIO_ERR_MAX])
{
    try {
        return open_file(path, info, result, err);
    } catch (const std::bad_alloc &) {
        *result = VT_OIIO_NOMEM;
        set_error(err, "out of memory");
    } catch (const std::exception &e) {
        *result = VT_OIIO_BAD_FILE;
        set_error(err, e.what());
    } catch (...) {
        *result = VT_OIIO_BAD_FILE;
        set_error(err, "unknown exception in OpenImageIO");
    }
    return nullptr;
}

VT_OIIO_EXPORT int vt_oiio_read(void *handle, uint32_t x, uint32_t y, uint32_t w, uint32_t h,
                                void *dst, size_t dst_stride, char err[VT_OIIO_ERR_MAX])
{
    Handle *hd = static_cast<Handle *>(handle);
    try {
        unsigned char *out = static_cast<unsigned char *>(dst);
        bool ok = hd->spec.tile_width > 0 && hd->spec.tile_height > 0
                      ? read_tiles(hd, x, y, w, h, out, dst_stride)
                      : read_scanlines(hd, x, y, w, h, out, dst_stride);
        if (ok)
            return VT_OIIO_OK;
        std::string msg = hd->in->geterror();
        set_error(err, msg.empty() ? "read failed" : msg);
        return VT_OIIO_BAD_FILE;
    } catch (const std::bad_alloc &) {
        set_error(err, "out of memory");
        return VT_OIIO_NOMEM;
    } catch (const std::exception &e) {
        set_error(err, e.what());
    } catch (...) {
        set_error(err, "unknown exception in OpenImageIO");
    }
    return VT_OIIO_BAD_FILE;
}

VT_OIIO_EXPORT void vt_oiio_close(void *handle)
{
    try {
        delete static_cast<Handle *>(handle);
    } catch (...) {
    }
}
