// image_oiio.cpp — the OpenImageIO wrapper behind image.h, built as a module
// (shadowlab-oiio.so) that image.c loads on the first image read or written
// (EXR layers, images read back; not the overlay sheets, image_sheet.cpp),
// so that verbs which touch no image never load OpenImageIO's ~260 libraries.
// C++ stays here and in image_sheet.cpp. Only sl_image_module is exported
// (-fvisibility=hidden).
#include "image_ops.h"
#include "image_module.hpp"
#include <OpenImageIO/half.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <cmath>
#include <cerrno>
#include <cstdint>
#include <mutex>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

using namespace OIIO;

// The SHA of the build that loaded the module, for the files' "Software" tag.
static const char *module_sha = "";

static bool IBA_text_defined(const char *font)
{
    return ImageBufAlgo::text_size("Ag", 16, font).defined();
}

static enum sl_err oiio_write_rgb8(const char *path, int w, int h,
                                           const unsigned char *rgb, struct sl_diag *d)
{
    std::string tmp = sl_image_tmp_name(path);
    auto out = ImageOutput::create(path);
    if (!out)
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "no image writer: %s", OIIO::geterror().c_str());
    ImageSpec spec(w, h, 3, TypeDesc::UINT8);
    spec.attribute("Software", std::string("shadowlab ") + module_sha);
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

static enum sl_err oiio_read_rgb8(const char *path, int *w, int *h, unsigned char **rgb,
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

static enum sl_err oiio_write_layers(const char *path, int w, int h, int nlayers,
                                             const char *const *names,
                                             const unsigned char *const *layers, int nattrs,
                                             const struct sl_image_attr *attrs, struct sl_diag *d)
{
    std::string tmp = sl_image_tmp_name(path);
    auto out = ImageOutput::create(path);
    if (!out)
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "no image writer: %s", OIIO::geterror().c_str());
    // Each layer twice: HALF under its name (the code as a number: what
    // viewers and `oiiotool --stats` show; UINT alone read as 0 there, being
    // scaled by 2^32) and UINT as "code.<name>" (the integer as it is).
    // Pixels are handed over in the channels' own formats (TypeUnknown):
    // converting floats to UINT would scale them.
    ImageSpec spec(w, h, 2 * nlayers, TypeDesc::HALF);
    spec.channelnames.clear();
    spec.channelformats.clear();
    for (int c = 0; c < nlayers; c++) {
        spec.channelnames.push_back(names[c]);
        spec.channelformats.push_back(TypeDesc::HALF);
    }
    for (int c = 0; c < nlayers; c++) {
        spec.channelnames.push_back(std::string("code.") + names[c]);
        spec.channelformats.push_back(TypeDesc::UINT32);
    }
    spec.attribute("Software", std::string("shadowlab ") + module_sha);
    spec.attribute("compression", "zip");
    for (int a = 0; a < nattrs; a++)
        spec.attribute(attrs[a].name, attrs[a].value);
    // one pixel in the file's channel order, packed: the halves, then the UINTs
    // (copied with memcpy: a UINT may sit at an odd offset)
    const size_t n = (size_t)w * (size_t)h, px = (size_t)nlayers * (2 + 4);
    std::unique_ptr<unsigned char[]> buf(new (std::nothrow) unsigned char[n * px]);
    if (!buf)
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "EXR buffer");
    // top-down rows, packed (OpenImageIO takes per-channel formats only contiguous)
    for (size_t i = 0; i < n; i++) {
        size_t x = i % (size_t)w, y = i / (size_t)w;
        unsigned char *p = buf.get() + (((size_t)h - 1 - y) * (size_t)w + x) * px;
        for (int c = 0; c < nlayers; c++) {
            half hv((float)layers[c][i]);
            std::memcpy(p + 2 * (size_t)c, &hv, 2);
            unsigned u = layers[c][i];
            std::memcpy(p + 2 * (size_t)nlayers + 4 * (size_t)c, &u, 4);
        }
    }
    if (!out->open(tmp, spec))
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "cannot write: %s", out->geterror().c_str());
    bool ok = out->write_image(TypeUnknown, buf.get());
    ok = out->close() && ok;
    if (!ok || std::rename(tmp.c_str(), path) != 0) {
        std::remove(tmp.c_str());
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "write failed");
    }
    return SL_OK;
}

static enum sl_err oiio_read_layer(const char *path, const char *name, int *w, int *h,
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
    /* file rows are top-down; hand back bottom-up like the rest of shadowlab.
     * A UINT channel as it is; a HALF or FLOAT one holds the code as a
     * number (reading it as UINT32 would scale 1.0 to 2^32 - 1) */
    bool ok;
    if (spec.channelformat(ch).basetype == TypeDesc::UINT32) {
        const stride_t ys = -(stride_t)spec.width * (stride_t)sizeof(unsigned);
        unsigned *last = *out + (size_t)(spec.height - 1) * (size_t)spec.width;
        ok = in->read_image(0, 0, ch, ch + 1, TypeDesc::UINT32, last, AutoStride, ys);
    } else {
        std::vector<float> f(n);
        ok = in->read_image(0, 0, ch, ch + 1, TypeDesc::FLOAT, f.data());
        for (int y = 0; ok && y < spec.height; y++)
            for (int x = 0; x < spec.width; x++) {
                float v = f[(size_t)y * (size_t)spec.width + (size_t)x];
                (*out)[(size_t)(spec.height - 1 - y) * (size_t)spec.width + (size_t)x] =
                    v > 0.0f ? (unsigned)std::lround(v) : 0u;
            }
    }
    in->close();
    if (!ok) {
        std::free(*out);
        *out = nullptr;
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot decode image");
    }
    return SL_OK;
}

static enum sl_err oiio_read_attr(const char *path, const char *name, char *out, int n,
                                          struct sl_diag *d)
{
    auto in = ImageInput::open(path);
    if (!in)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read image: %s", OIIO::geterror().c_str());
    std::string v = in->spec().get_string_attribute(name, "\x01");
    in->close();
    if (v == "\x01")
        return sl_fail(d, SL_E_IO, path, 0, name, "no such attribute");
    std::snprintf(out, (size_t)n, "%s", v.c_str());
    return SL_OK;
}

static enum sl_err oiio_write_floats(const char *path, int w, int h, int nch, const char *const *names,
                                     const float *const *chans, int nattrs, const struct sl_image_attr *attrs,
                                     struct sl_diag *d)
{
    std::string tmp = sl_image_tmp_name(path);
    auto out = ImageOutput::create(path);
    if (!out)
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "no image writer: %s", OIIO::geterror().c_str());
    ImageSpec spec(w, h, nch, TypeDesc::FLOAT);
    spec.channelnames.clear();
    for (int c = 0; c < nch; c++)
        spec.channelnames.push_back(names[c]);
    spec.alpha_channel = -1;
    for (int c = 0; c < nch; c++)
        if (std::strcmp(names[c], "A") == 0)
            spec.alpha_channel = c;
    spec.attribute("Software", std::string("shadowlab ") + module_sha);
    spec.attribute("compression", "zip");
    for (int a = 0; a < nattrs; a++)
        spec.attribute(attrs[a].name, attrs[a].value);
    const size_t n = (size_t)w * (size_t)h;
    std::vector<float> buf;
    try {
        buf.resize(n * (size_t)nch);
    } catch (...) {
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "EXR buffer");
    }
    for (size_t i = 0; i < n; i++) {   // interleaved, top-down
        size_t x = i % (size_t)w, y = i / (size_t)w;
        float *p = buf.data() + (((size_t)h - 1 - y) * (size_t)w + x) * (size_t)nch;
        for (int c = 0; c < nch; c++)
            p[c] = chans[c][i];
    }
    if (!out->open(tmp, spec))
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "cannot write: %s", out->geterror().c_str());
    bool ok = out->write_image(TypeDesc::FLOAT, buf.data());
    ok = out->close() && ok;
    if (!ok || std::rename(tmp.c_str(), path) != 0) {
        std::remove(tmp.c_str());
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "write failed");
    }
    return SL_OK;
}

static enum sl_err oiio_read_floats(const char *path, struct sl_image_floats *im, struct sl_diag *d)
{
    // a PNG's alpha as stored: OpenImageIO would otherwise multiply it in
    ImageSpec cfg;
    cfg.attribute("oiio:UnassociatedAlpha", 1);
    auto in = ImageInput::open(path, &cfg);
    if (!in)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read image: %s", OIIO::geterror().c_str());
    const ImageSpec &spec = in->spec();
    if (spec.nchannels < 1 || spec.nchannels > SL_IMAGE_MAX_CH || spec.width < 1 || spec.height < 1 ||
        (double)spec.width * (double)spec.height > (double)(1u << 28)) {
        in->close();
        return sl_fail(d, SL_E_USAGE, path, 0, NULL, "%d x %d pixels of %d channels: at most %d channels and 2^28 pixels",
                       spec.width, spec.height, spec.nchannels, SL_IMAGE_MAX_CH);
    }
    im->w = spec.width;
    im->h = spec.height;
    im->nch = spec.nchannels;
    TypeDesc f = spec.format;
    for (int c = 0; c < spec.nchannels; c++) {   // the widest channel says it
        TypeDesc cf = spec.channelformat(c);
        if (cf.size() > f.size())
            f = cf;
    }
    im->bits = (int)f.size() * 8;
    im->is_float = f.basetype == TypeDesc::HALF || f.basetype == TypeDesc::FLOAT || f.basetype == TypeDesc::DOUBLE;
    for (int c = 0; c < spec.nchannels; c++)
        std::snprintf(im->names[c], sizeof im->names[c], "%s", spec.channelnames[(size_t)c].c_str());
    std::snprintf(im->format, sizeof im->format, "%s", in->format_name());
    const size_t n = (size_t)im->w * (size_t)im->h, nch = (size_t)im->nch;
    im->px = (float *)std::malloc(n * nch * sizeof(float));
    if (!im->px) {
        in->close();
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "image buffer");
    }
    // file rows are top-down; bottom-up here like the rest of shadowlab
    const stride_t ys = -(stride_t)im->w * (stride_t)nch * (stride_t)sizeof(float);
    float *last = im->px + (size_t)(im->h - 1) * (size_t)im->w * nch;
    bool ok = in->read_image(0, 0, 0, im->nch, TypeDesc::FLOAT, last, AutoStride, ys);
    in->close();
    if (!ok) {
        std::free(im->px);
        im->px = nullptr;
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot decode image");
    }
    return SL_OK;
}

// The sheets' font here (where the sheet module's own FreeType could not
// open DejaVu Sans's file): DejaVu Sans by its full path, else by name
// anywhere OpenImageIO looks, else OpenImageIO's default; NULL when none
// loads (the sheet then has no text). Resolved once, to a
// full path where possible: OpenImageIO searches its font folders on every
// call given a bare name (measured: most of a sheet's time).
static const std::string *sheet_font()
{
    static std::string font;
    static bool found = false;
    static std::once_flag once;
    std::call_once(once, [] {
        // one thread per ImageBufAlgo call: the sheet's images are small, and
        // on a busy machine a pool's hand-offs cost more than they save
        OIIO::attribute("threads", 1);
        for (const char *name : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "DejaVuSans", ""}) {
            if (name[0] == '/' && !Filesystem::exists(name))
                continue;
            if (IBA_text_defined(name)) {
                font = name;
                found = true;
                break;
            }
        }
        (void)OIIO::geterror();   // a failed lookup leaves a message: not ours to print
    });
    return found ? &font : nullptr;
}

// ---- the sheets' glyphs, when their font file is missing ------------------
// The sheet module (image_sheet.cpp) draws glyphs with FreeType from
// DejaVu Sans's file; where that file is missing it asks here, and gets
// render_text's own drawing through OpenImageIO's font search (sheet_font
// above). Also the tests' reference for the FreeType glyphs.

static std::string utf8_of(uint32_t c)
{
    std::string s;
    if (c < 0x80) {
        s += (char)c;
    } else if (c < 0x800) {
        s += (char)(0xC0 | (c >> 6));
        s += (char)(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
        s += (char)(0xE0 | (c >> 12));
        s += (char)(0x80 | ((c >> 6) & 0x3F));
        s += (char)(0x80 | (c & 0x3F));
    } else {
        s += (char)(0xF0 | (c >> 18));
        s += (char)(0x80 | ((c >> 12) & 0x3F));
        s += (char)(0x80 | ((c >> 6) & 0x3F));
        s += (char)(0x80 | (c & 0x3F));
    }
    return s;
}

// The glyph of code point c at size fs through render_text (image_ops.h).
// Its box is text_size of the character alone: x from bitmap_left to
// bitmap_left + width + 1, y from -bitmap_top to rows - bitmap_top + 1
// (imagebufalgo_draw.cpp); its advance is the difference between the right
// ends of "cc" and "c" (advances are >= 0 in a horizontal font, so the
// second copy's end is the further one).
static int oiio_glyph(int fs, uint32_t c, struct sl_image_glyph *g)
{
    namespace IBA = ImageBufAlgo;
    std::memset(g, 0, sizeof *g);
    const std::string *font = sheet_font();
    if (!font)
        return -1;
    static std::mutex mu;   // OpenImageIO's error state is per thread; the font's lookup is not
    std::lock_guard<std::mutex> lock(mu);
    const std::string one = utf8_of(c);
    ROI r = IBA::text_size(one, fs, *font);
    if (!r.defined() || r.xend <= r.xbegin || r.yend <= r.ybegin)
        return 0;   // no such glyph: skipped, as render_text skips it
    ROI r2 = IBA::text_size(one + one, fs, *font);
    g->left = r.xbegin;
    g->top = -r.ybegin;
    g->w = r.width() - 1;
    g->h = r.height() - 1;
    g->adv = r2.defined() ? r2.xend - r.xend : 0;
    std::vector<float> box((size_t)r.width() * (size_t)r.height(), 0.0f);
    // white text over black in a one-channel float image placed at the
    // glyph's own box: each pixel is then exactly the glyph's bitmap / 255
    ImageSpec spec(r.width(), r.height(), 1, TypeDesc::FLOAT);
    spec.x = spec.full_x = r.xbegin;
    spec.y = spec.full_y = r.ybegin;
    ImageBuf tb(spec, box.data());
    const float one_f = 1.0f;
    IBA::render_text(tb, 0, 0, one, fs, *font, cspan<float>(&one_f, 1));
    (void)OIIO::geterror();
    // keep w * h (the box is one wider and taller than the bitmap)
    if (g->w > 0 && g->h > 0) {
        g->a = (float *)std::malloc((size_t)g->w * (size_t)g->h * sizeof(float));
        if (!g->a)
            return 0;
        for (int j = 0; j < g->h; j++)
            for (int i = 0; i < g->w; i++)
                g->a[(size_t)j * (size_t)g->w + (size_t)i] = box[(size_t)j * (size_t)r.width() + (size_t)i];
    }
    return 1;
}

extern "C" __attribute__((visibility("default"))) const struct sl_image_ops *sl_image_module(int abi,
                                                                                        const char *git_sha)
{
    static const struct sl_image_ops ops = {
        oiio_write_rgb8, oiio_write_layers, oiio_read_layer, oiio_read_rgb8, oiio_read_attr,
        oiio_write_floats, oiio_read_floats, oiio_glyph,
    };
    if (abi != SL_IMAGE_ABI)
        return NULL;
    module_sha = git_sha ? git_sha : "";
    return &ops;
}
