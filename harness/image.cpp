// image.cpp — thin OpenImageIO wrapper behind image.h. C++ stays here.
#include "image.h"
#include "provenance.h"
#include <OpenImageIO/imageio.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

using namespace OIIO;

static std::string tmp_name(const std::string &path)
{
    // keep the extension so OpenImageIO picks the same format
    size_t slash = path.find_last_of('/');
    size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return path + ".tmp";
    return path.substr(0, dot) + ".tmp" + path.substr(dot);
}

extern "C" enum sl_err sl_image_write_rgb8(const char *path, int w, int h,
                                           const unsigned char *rgb, struct sl_diag *d)
{
    std::string tmp = tmp_name(path);
    auto out = ImageOutput::create(path);
    if (!out)
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "no image writer: %s", OIIO::geterror().c_str());
    ImageSpec spec(w, h, 3, TypeDesc::UINT8);
    spec.attribute("Software", std::string("shadowlab ") + sl_git_sha());
    if (!out->open(tmp, spec))
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "cannot write: %s", out->geterror().c_str());
    // bottom-up rows: start at the last row and walk with a negative stride
    const stride_t ys = -(stride_t)w * 3;
    const unsigned char *last = rgb + (size_t)(h - 1) * (size_t)w * 3;
    bool ok = out->write_image(TypeDesc::UINT8, last, AutoStride, ys);
    ok = out->close() && ok;
    if (!ok || std::rename(tmp.c_str(), path) != 0) {
        std::remove(tmp.c_str());
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "write failed");
    }
    return SL_OK;
}

extern "C" enum sl_err sl_image_read_rgb8(const char *path, int *w, int *h, unsigned char **rgb,
                                          struct sl_diag *d)
{
    auto in = ImageInput::open(path);
    if (!in)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read image: %s", OIIO::geterror().c_str());
    const ImageSpec &spec = in->spec();
    *w = spec.width;
    *h = spec.height;
    size_t n = (size_t)spec.width * (size_t)spec.height * 3;
    *rgb = (unsigned char *)std::malloc(n);
    if (!*rgb)
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "image buffer");
    bool ok = in->read_image(0, 0, 0, 3, TypeDesc::UINT8, *rgb);
    in->close();
    if (!ok) {
        std::free(*rgb);
        *rgb = nullptr;
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot decode image");
    }
    return SL_OK;
}
