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

extern "C" enum sl_err sl_image_write_layers(const char *path, int w, int h, int nlayers,
                                             const char *const *names,
                                             const unsigned char *const *layers, struct sl_diag *d)
{
    std::string tmp = tmp_name(path);
    auto out = ImageOutput::create(path);
    if (!out)
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "no image writer: %s", OIIO::geterror().c_str());
    ImageSpec spec(w, h, nlayers, TypeDesc::UINT32);
    spec.channelnames.clear();
    for (int c = 0; c < nlayers; c++)
        spec.channelnames.push_back(names[c]);
    spec.attribute("Software", std::string("shadowlab ") + sl_git_sha());
    spec.attribute("compression", "zip");
    const size_t n = (size_t)w * (size_t)h;
    std::unique_ptr<unsigned[]> buf(new (std::nothrow) unsigned[n * (size_t)nlayers]);
    if (!buf)
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "EXR buffer");
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < nlayers; c++)
            buf[i * (size_t)nlayers + (size_t)c] = layers[c][i];
    if (!out->open(tmp, spec))
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "cannot write: %s", out->geterror().c_str());
    const stride_t ys = -(stride_t)w * nlayers * (stride_t)sizeof(unsigned);
    const unsigned *last = buf.get() + (size_t)(h - 1) * (size_t)w * (size_t)nlayers;
    bool ok = out->write_image(TypeDesc::UINT32, last, AutoStride, ys);
    ok = out->close() && ok;
    if (!ok || std::rename(tmp.c_str(), path) != 0) {
        std::remove(tmp.c_str());
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "write failed");
    }
    return SL_OK;
}

extern "C" enum sl_err sl_image_read_layer(const char *path, const char *name, int *w, int *h,
                                           unsigned **out, struct sl_diag *d)
{
    auto in = ImageInput::open(path);
    if (!in)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read image: %s", OIIO::geterror().c_str());
    const ImageSpec &spec = in->spec();
    int ch = -1;
    for (int c = 0; c < spec.nchannels; c++)
        if (spec.channelnames[(size_t)c] == name)
            ch = c;
    if (ch < 0) {
        in->close();
        return sl_fail(d, SL_E_IO, path, 0, name, "no such channel");
    }
    *w = spec.width;
    *h = spec.height;
    size_t n = (size_t)spec.width * (size_t)spec.height;
    *out = (unsigned *)std::malloc(n * sizeof(unsigned));
    if (!*out)
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "image buffer");
    /* file rows are top-down; hand back bottom-up like the rest of shadowlab */
    const stride_t ys = -(stride_t)spec.width * (stride_t)sizeof(unsigned);
    unsigned *last = *out + (size_t)(spec.height - 1) * (size_t)spec.width;
    bool ok = in->read_image(0, 0, ch, ch + 1, TypeDesc::UINT32, last, AutoStride, ys);
    in->close();
    if (!ok) {
        std::free(*out);
        *out = nullptr;
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot decode image");
    }
    return SL_OK;
}
