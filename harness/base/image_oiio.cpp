// image_oiio.cpp — the OpenImageIO wrapper behind image.h, built as a module
// (shadowlab-oiio.so) that image.c loads on the first image read or written,
// so that verbs which touch no image never load OpenImageIO's ~260 libraries.
// C++ stays here. Only sl_image_module is exported (-fvisibility=hidden).
#include "image_ops.h"
#include <OpenImageIO/half.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <cmath>
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

static std::string tmp_name(const std::string &path)
{
    // keep the extension so OpenImageIO picks the same format
    size_t slash = path.find_last_of('/');
    size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return path + ".tmp";
    return path.substr(0, dot) + ".tmp" + path.substr(dot);
}

static enum sl_err oiio_write_rgb8(const char *path, int w, int h,
                                           const unsigned char *rgb, struct sl_diag *d)
{
    std::string tmp = tmp_name(path);
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
    std::string tmp = tmp_name(path);
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

// The sheet's font: DejaVu Sans (Debian's fonts-dejavu-core) by its full
// path, else by name anywhere OpenImageIO looks, else OpenImageIO's default;
// NULL when none loads (the sheet then has no text). Resolved once, to a
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

static enum sl_err oiio_write_sheet(const char *path, const struct sl_image_sheet *s,
                                            struct sl_diag *d)
{
    namespace IBA = ImageBufAlgo;
    const int W = s->w, H = s->h;
    // the frame, top-down like the file: the caller's bottom-up rows wrapped
    // with a negative stride, never copied
    const stride_t row = (stride_t)W * 3;
    ImageBuf frame(ImageSpec(W, H, 3, TypeDesc::UINT8),
                   const_cast<unsigned char *>(s->rgb) + (size_t)(H - 1) * (size_t)row, 3, -row);
    int vx = 0, vy = 0, vw = W, vh = H;
    if (s->view[2] > 0) {
        vx = s->view[0];
        vw = s->view[2];
        vh = s->view[3];
        vy = H - (s->view[1] + vh);
    }
    const std::string *font = sheet_font();
    // text about 1/48 of the frame's height (21 px at 1024), 12 to 22 px
    const int fs = std::clamp(std::max(vh, H) / 48, 12, 22);
    const int M = fs / 2 + 4, line = fs * 3 / 2;
    auto textw = [&](const std::string &t) {
        if (!font || t.empty())
            return 0;
        ROI r = IBA::text_size(t, fs, *font);
        return r.defined() ? r.width() : 0;
    };
    const float white[3] = {1, 1, 1}, black[3] = {0, 0, 0}, rim[3] = {0.55f, 0.55f, 0.55f};

    // insets: nearest-neighbour zooms of their windows (ImageBufAlgo::resample
    // without interpolation), cut from the frame before anything is marked
    const int z = std::max(1, s->zoom), ni = std::clamp(s->ninsets, 0, SL_SHEET_MAX_INSETS);
    std::vector<ImageBuf> zoomed((size_t)ni);
    std::vector<std::vector<unsigned char>> zpx((size_t)ni);
    std::vector<ROI> win((size_t)ni);
    // laid out in columns beside the view, a new column when the next would
    // reach below the view (a short crop gets its insets side by side)
    std::vector<int> ix((size_t)ni), iy((size_t)ni);
    int colx = 0, colw = 0, cy = 0, colh = 0;
    for (int k = 0; k < ni; k++) {
        const int *b = s->inset[k];
        win[(size_t)k] = ROI(b[0], b[0] + b[2], H - (b[1] + b[3]), H - b[1], 0, 1, 0, 3);
        // each source pixel a z x z square, straight from the caller's rows:
        // what ImageBufAlgo::resample without interpolation gives for an
        // integer factor (source x = floor((X + 0.5) / z) = X / z), without
        // its per-pixel iterators (12% of a sheet's time, measured)
        const int zw = b[2] * z, zh = b[3] * z, wx = b[0], wy = H - (b[1] + b[3]);
        std::vector<unsigned char> &q = zpx[(size_t)k];
        q.resize((size_t)zw * (size_t)zh * 3);
        for (int Y = 0; Y < zh; Y++) {
            const unsigned char *src = s->rgb + ((size_t)(H - 1 - (wy + Y / z)) * (size_t)W + (size_t)wx) * 3;
            unsigned char *dst = &q[(size_t)Y * (size_t)zw * 3];
            for (int X = 0; X < zw; X++)
                std::memcpy(dst + (size_t)X * 3, src + (size_t)(X / z) * 3, 3);
        }
        zoomed[(size_t)k].reset(ImageSpec(zw, zh, 3, TypeDesc::UINT8), q.data());
        int bh = (font ? line : 0) + b[3] * z + M;
        if (cy > 0 && cy + bh > vh + M) {
            colx += colw + M;
            colw = 0;
            cy = 0;
        }
        ix[(size_t)k] = colx;
        iy[(size_t)k] = cy;
        colw = std::max({colw, b[2] * z, textw(s->inset_caption[k])});
        cy += bh;
        colh = std::max(colh, cy);
    }
    colw += colx;

    // the layout: title, the view at 1:1 with the insets beside it, the legend
    std::string title = s->title;
    const int titleh = font && !title.empty() ? line : 0;
    const int bodyw = vw + (ni > 0 ? M + colw : 0), bodyh = std::max(vh, colh);
    const int sw = 2 * M + std::max(bodyw, textw(title));
    std::vector<int> lx, ly;
    int x = M, y = 0, rows = s->nlegend > 0 ? 1 : 0;
    for (int k = 0; k < s->nlegend && k < SL_SHEET_MAX_LEGEND; k++) {
        int ew = fs + 6 + textw(s->legend_text[k]) + 2 * M;
        if (x > M && x + ew > sw - M) {
            x = M;
            y += line;
            rows++;
        }
        lx.push_back(x);
        ly.push_back(y);
        x += ew;
    }
    const int top = M + titleh, legy = top + bodyh + M;
    const int sh = legy + rows * line + M;
    // a white sheet in our own buffer; the view copied into it row by row
    // (memcpy: ImageBufAlgo::paste of a 1024² frame measured 13-15 ms here,
    // the rows 0.1 ms, and this is per cell)
    std::vector<unsigned char> px((size_t)sw * (size_t)sh * 3, 255);
    for (int j = 0; j < vh; j++)
        std::memcpy(&px[((size_t)(top + j) * (size_t)sw + (size_t)M) * 3],
                    s->rgb + ((size_t)(H - 1 - (vy + j)) * (size_t)W + (size_t)vx) * 3, (size_t)vw * 3);
    ImageBuf sheet(ImageSpec(sw, sh, 3, TypeDesc::UINT8), px.data());
    const int ox = M - vx, oy = top - vy;   // frame (top-down) to sheet

    // the windows marked on the view: a white 2-px box just outside each and
    // its number; then, inside the view, every error pixel put back as it
    // was, so a mark never covers one
    const ROI vroi(M, M + vw, top, top + vh, 0, 1, 0, 3);
    for (int k = 0; k < ni; k++) {
        const ROI &r = win[(size_t)k];
        int x0 = r.xbegin + ox, y0 = r.ybegin + oy, x1 = r.xend + ox, y1 = r.yend + oy;
        IBA::render_box(sheet, x0 - 2, y0 - 2, x1 + 1, y1 + 1, white, false, vroi);
        IBA::render_box(sheet, x0 - 1, y0 - 1, x1, y1, white, false, vroi);
        if (font) {
            int ty = y0 - 4 - fs >= top ? y0 - 4 : y1 + 4 + fs;
            IBA::render_text(sheet, x0 - 2, ty, std::to_string(k + 1), fs, *font, white, IBA::TextAlignX::Left,
                             IBA::TextAlignY::Baseline, 0, vroi);
        }
        if (!s->keep)
            continue;
        ROI u = roi_intersection(ROI(x0 - 3, x1 + 3 + fs, y0 - 8 - 2 * fs, y1 + 8 + 2 * fs, 0, 1, 0, 3), vroi);
        ROI uf(u.xbegin - ox, u.xend - ox, u.ybegin - oy, u.yend - oy, 0, 1, 0, 3);   // in the frame
        const stride_t krow = (stride_t)W;
        ImageBuf kb(ImageSpec(W, H, 1, TypeDesc::UINT8),
                    const_cast<unsigned char *>(s->keep) + (size_t)(H - 1) * (size_t)W, 1, -krow);
        ImageBuf k3 = IBA::channels(IBA::cut(kb, ROI(uf.xbegin, uf.xend, uf.ybegin, uf.yend, 0, 1, 0, 1)), 3,
                                    {0, 0, 0});
        ImageBuf was = IBA::cut(frame, uf).copy(TypeDesc::FLOAT);
        ImageBuf now = IBA::cut(sheet, u).copy(TypeDesc::FLOAT);
        ImageBuf back = IBA::mad(k3, IBA::sub(was, now), now);   // keep ? was : now
        IBA::paste(sheet, u.xbegin, u.ybegin, 0, 0, back);
    }

    if (titleh)
        IBA::render_text(sheet, M, M + fs, title, fs, *font, black);
    std::string where[SL_SHEET_MAX_INSETS];
    for (int k = 0; k < ni; k++) {
        const ROI &r = win[(size_t)k];
        int cx = M + vw + M + ix[(size_t)k], cy = top + iy[(size_t)k];
        if (font)
            IBA::render_text(sheet, cx, cy + fs, s->inset_caption[k], fs, *font, black);
        int py = cy + (font ? line : 0);
        IBA::paste(sheet, cx, py, 0, 0, zoomed[(size_t)k]);
        IBA::render_box(sheet, cx - 1, py - 1, cx + r.width() * z, py + r.height() * z, rim);
        where[k] = std::to_string(r.xbegin) + " " + std::to_string(r.ybegin) + " " + std::to_string(r.width()) +
                   " " + std::to_string(r.height()) + " " + std::to_string(cx) + " " + std::to_string(py) + " " +
                   std::to_string(z);
    }
    std::string legend;
    for (size_t k = 0; k < lx.size(); k++) {
        const unsigned char *c = s->legend_rgb[k];
        const float cf[3] = {c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f};
        int ex = lx[k], ey = legy + ly[k];
        IBA::fill(sheet, cf, ROI(ex, ex + fs, ey, ey + fs, 0, 1, 0, 3));
        IBA::render_box(sheet, ex, ey, ex + fs - 1, ey + fs - 1, black);
        if (font)
            IBA::render_text(sheet, ex + fs + 6, ey + fs - fs / 5, s->legend_text[k], fs, *font, black);
        legend += (k ? "; " : "") + std::string(s->legend_text[k]);
    }

    ImageSpec &spec = sheet.specmod();
    spec.attribute("Software", std::string("shadowlab ") + module_sha);
    if (!title.empty())
        spec.attribute("ImageDescription", title);
    spec.attribute("shadowlab:view", std::to_string(vx) + " " + std::to_string(vy) + " " + std::to_string(vw) + " " +
                                         std::to_string(vh) + " " + std::to_string(M) + " " + std::to_string(top));
    for (int k = 0; k < ni; k++)
        spec.attribute("shadowlab:inset" + std::to_string(k + 1), where[k]);
    spec.attribute("shadowlab:legend", legend);
    spec.attribute("shadowlab:text", font ? "1" : "0");
    for (int a = 0; a < s->nattrs; a++)
        spec.attribute(s->attrs[a].name, s->attrs[a].value);
    // PNG: the "sub" filter alone (libpng's PNG_FILTER_SUB) at zlib level 3.
    // SUB: 31 ms for a 1386 x 1230 sheet against 81 ms with libpng's
    // adaptive choice, and a smaller file on these flat images. Level 3
    // against 6 (20 sheets of the aliasing study, CPU per sheet, median of
    // 5): 5.1 ms against 9.4 ms, for files 25% larger (1.15 MB against
    // 0.92 MB); level 1 saves only 0.2 ms more for 34% (measured here).
    // Again with the sheets written by the run's writer thread (issue 20;
    // the 60 sheets of Moderno's Primitives, 1024² frames, 3 runs each,
    // alternating, load 5-7): level 1 took 45.5-58.0 ms of the writer's CPU
    // per sheet against 43.8-49.6 at level 3 (composing the sheet, not
    // deflate, is most of it) for 4.92 MB against 4.50 MB: level 3 stays.
    // No cheaper format by option: the time is in composing (text, boxes,
    // the insets), which any format pays, and off the cells' path now.
    spec.attribute("png:compressionLevel", 3);
    spec.attribute("png:filter", 0x10);
    if (sheet.has_error())
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "composing the sheet: %s", sheet.geterror().c_str());
    std::string tmp = tmp_name(path);
    if (!sheet.write(tmp) || std::rename(tmp.c_str(), path) != 0) {
        std::remove(tmp.c_str());
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "write failed: %s", sheet.geterror().c_str());
    }
    return SL_OK;
}

extern "C" __attribute__((visibility("default"))) const struct sl_image_ops *sl_image_module(int abi,
                                                                                        const char *git_sha)
{
    static const struct sl_image_ops ops = {
        oiio_write_rgb8, oiio_write_layers, oiio_read_layer, oiio_read_rgb8, oiio_read_attr, oiio_write_sheet,
    };
    if (abi != SL_IMAGE_ABI)
        return NULL;
    module_sha = git_sha ? git_sha : "";
    return &ops;
}
