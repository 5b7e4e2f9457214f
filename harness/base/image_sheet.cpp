// image_sheet.cpp — the overlay sheet (image.h: sl_image_write_sheet),
// built as its own module (shadowlab-sheet.so) that image.c loads on the
// first sheet written. Issue 20: the sheet needs only glyphs, a deflater
// and plain memory, and reaching its glyphs through OpenImageIO loaded
// OpenImageIO's ~260 libraries into every run that wrote overlays (0.5 s
// of CPU, relocations and constructors, for one render_text per glyph).
// The glyphs now come from FreeType itself, called as render_text calls
// it, and OpenImageIO is loaded only when the font file is missing (its
// font search then finds another) or a run writes EXR or reads an image.
// C++ stays here and in image_oiio.cpp. Only sl_sheet_module is exported.
#include "image_ops.h"
#include "image_module.hpp"
#include <ft2build.h>
#include FT_FREETYPE_H
#include <libdeflate.h>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

// The SHA of the build that loaded the module, for the files' "Software" tag.
static const char *module_sha = "";

// ---- the sheet, composed in plain memory ---------------------------------
// Issue 20: composing a sheet through ImageBuf (per-pixel getpixel/setpixel
// in render_text, iterators in render_box, paste, fill, and the float
// round trip that put errors back) and loading the font file anew for every
// text call (FreeType's hinting program, TT_RunIns, on every glyph of every
// string) was most of the writer's CPU. Here the sheet is a byte buffer,
// boxes and swatches are written directly, and each glyph is drawn once
// per (size, character) per process (by FreeType, below) and then blitted.
// Everything below reproduces ImageBufAlgo's own arithmetic, so a sheet is
// the same file, byte for byte, as the one ImageBufAlgo composed (checked on
// the 240 sheets of the Moderno study; overlay:: reads them back).

// OpenImageIO's conversions between 8-bit and float pixels (fmath.h:
// u8 * (1/255); round(v * 255) clamped), used where a colour is blended.
static inline float u8_to_f(unsigned char b) { return (float)b * (1.0f / 255.0f); }
static inline unsigned char f_to_u8(float v)
{
    return (unsigned char)std::clamp(v * 255.0f + 0.5f, 0.0f, 255.0f);
}

// One glyph as FreeType renders it at one pixel size (what render_text
// writes: bitmap / 255), its placement relative to the pen and its advance.
struct sheet_glyph {
    bool ok = false;             // FreeType had it (render_text skips those it has not)
    int left = 0, top = 0, w = 0, h = 0, adv = 0;
    std::vector<float> a;        // w * h, top row first
};

struct glyph_cache {
    std::mutex mu;
    std::map<std::pair<int, uint32_t>, sheet_glyph> g;
};
static glyph_cache glyphs;

// Where glyphs come from: FreeType, called as OpenImageIO's render_text
// calls it, on the font file itself (SHEET_FONT); or, when that file is not
// there, the image module's glyph (OpenImageIO's render_text and its font
// search); or nowhere (no font: the sheet has no text).
enum glyph_source { GLYPHS_NONE, GLYPHS_FREETYPE, GLYPHS_MODULE };
static const char *const SHEET_FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
static sl_image_glyph_fn module_glyph;   // image.c's, given at load

// FreeType's state, under glyphs.mu: one face per pixel size, each set to
// its size once (render_text opens the file and sets the size, running the
// font's hinting program, for every string: issue 20).
struct ft_state {
    FT_Library lib = nullptr;
    std::map<int, FT_Face> face;
};
static ft_state ft;

// The face at pixel size fs, or null when FreeType cannot open or size it
// (as render_text then draws nothing).
static FT_Face ft_face(int fs)
{
    auto it = ft.face.find(fs);
    if (it != ft.face.end())
        return it->second;
    FT_Face f = nullptr;
    if (ft.lib && FT_New_Face(ft.lib, SHEET_FONT, 0, &f) == 0 && FT_Set_Pixel_Sizes(f, 0, (FT_UInt)fs) != 0) {
        FT_Done_Face(f);
        f = nullptr;
    }
    ft.face[fs] = f;
    return f;
}

// The glyph of c at fs from FreeType, as render_text takes it: FT_Load_Char
// with FT_LOAD_RENDER (a failure skips the character), the bitmap / 255,
// placed at bitmap_left, -bitmap_top; the pen advanced by advance.x >> 6
// (the sheet's layout measures it as the step between the right ends of
// "c" and "cc", never negative). overlay::glyphs_as_oiio compares every
// glyph the sheets draw with OpenImageIO's.
static int ft_glyph(int fs, uint32_t c, struct sl_image_glyph *g)
{
    std::memset(g, 0, sizeof *g);
    FT_Face f = ft_face(fs);
    if (!f)
        return 0;
    if (FT_Load_Char(f, c, FT_LOAD_RENDER) != 0)
        return 0;
    const FT_GlyphSlot slot = f->glyph;
    const FT_Bitmap &bm = slot->bitmap;
    g->left = slot->bitmap_left;
    g->top = slot->bitmap_top;
    g->w = (int)bm.width;
    g->h = (int)bm.rows;
    g->adv = std::max(0, (int)(slot->advance.x >> 6));
    if (g->w > 0 && g->h > 0) {
        g->a = (float *)std::malloc((size_t)g->w * (size_t)g->h * sizeof(float));
        if (!g->a)
            return 0;
        for (int j = 0; j < g->h; j++)
            for (int i = 0; i < g->w; i++)
                g->a[(size_t)j * (size_t)g->w + (size_t)i] = bm.buffer[bm.pitch * j + i] / 255.0f;
    }
    return 1;
}

// Chooses the source once: the font file through FreeType when it opens
// (what OpenImageIO's text_size checks of a font), else the module's.
static glyph_source sheet_glyphs()
{
    static glyph_source src = GLYPHS_NONE;
    static std::once_flag once;
    std::call_once(once, [] {
        if (FT_Init_FreeType(&ft.lib) != 0)
            ft.lib = nullptr;
        if (ft.lib && ft_face(16)) {
            src = GLYPHS_FREETYPE;
            return;
        }
        struct sl_image_glyph g;
        if (module_glyph && module_glyph(16, 'A', &g) >= 0) {
            std::free(g.a);
            src = GLYPHS_MODULE;
        }
    });
    return src;
}

// The glyph of code point c at size fs, drawn once (the caller holds
// glyphs.mu).
static const sheet_glyph &glyph_of(int fs, uint32_t c)
{
    auto key = std::make_pair(fs, c);
    auto it = glyphs.g.find(key);
    if (it != glyphs.g.end())
        return it->second;
    sheet_glyph &gl = glyphs.g[key];
    struct sl_image_glyph g;
    const glyph_source src = sheet_glyphs();
    const int got = src == GLYPHS_FREETYPE ? ft_glyph(fs, c, &g)
                    : src == GLYPHS_MODULE ? module_glyph(fs, c, &g)
                                           : -1;
    if (got <= 0)
        return gl;   // no such glyph: skipped, as render_text skips it
    gl.left = g.left;
    gl.top = g.top;
    gl.w = g.w;
    gl.h = g.h;
    gl.adv = g.adv;
    gl.a.assign(g.a, g.a + (size_t)g.w * (size_t)g.h);
    std::free(g.a);
    gl.ok = true;
    return gl;
}

// A string's characters as OpenImageIO 2.4's Strutil::utf8_to_unicode
// gives them to render_text, so the sheets draw what they drew. It
// validates UTF-8 as a DFA would (an ill-formed byte stops the string: its
// reject state is final) but restarts the code point at every byte, so a
// multi-byte character comes out as its last byte's six low bits: "é" (C3
// A9) is drawn as ")" (0x29), as `oiiotool --text` draws it
// (overlay::text_as_oiio compares the two on such a title). ASCII is as it
// is. The sheets' own strings are ASCII; a config's names are UTF-8 that
// libyaml has checked.
static void utf8_decode(const std::string &t, std::vector<uint32_t> &u)
{
    u.clear();
    const size_t n = t.size();
    for (size_t i = 0; i < n;) {
        const unsigned b = (unsigned char)t[i];
        if (b < 0x80) {
            u.push_back(b);
            i++;
            continue;
        }
        // the sequence's length and the range of its second byte
        int more;
        unsigned lo = 0x80, hi = 0xBF;
        if (b >= 0xC2 && b <= 0xDF) {
            more = 1;
        } else if (b >= 0xE0 && b <= 0xEF) {
            more = 2;
            lo = b == 0xE0 ? 0xA0 : 0x80;   // no overlong form
            hi = b == 0xED ? 0x9F : 0xBF;   // no surrogate
        } else if (b >= 0xF0 && b <= 0xF4) {
            more = 3;
            lo = b == 0xF0 ? 0x90 : 0x80;
            hi = b == 0xF4 ? 0x8F : 0xBF;   // nothing above U+10FFFF
        } else {
            return;   // a stray continuation byte, C0, C1, F5-FF: rejected
        }
        for (int k = 1; k <= more; k++) {
            if (i + (size_t)k >= n)
                return;   // cut short: nothing more comes out
            const unsigned c = (unsigned char)t[i + (size_t)k];
            if (c < (k == 1 ? lo : 0x80) || c > (k == 1 ? hi : 0xBF))
                return;
        }
        u.push_back((unsigned char)t[i + (size_t)more] & 0x3Fu);
        i += (size_t)more + 1;
    }
}

// A string's glyphs and its box relative to the pen at the baseline, as
// text_size_from_unicode computes it (including its one-pixel margins).
struct sheet_text {
    std::vector<std::pair<int, const sheet_glyph *>> g;   // pen x, glyph
    std::vector<int> gy;                                     // pen y ('\n' moves it)
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;                      // x1, y1 exclusive
    bool any = false;
};

static sheet_text layout_text(const std::string &t, int fs)
{
    sheet_text st;
    std::vector<uint32_t> u;
    utf8_decode(t, u);
    int x = 0, y = 0;
    st.x0 = st.y0 = std::numeric_limits<int>::max();
    st.x1 = st.y1 = std::numeric_limits<int>::min();
    for (uint32_t c : u) {
        if (c == '\n') {
            x = 0;
            y += fs;
            continue;
        }
        const sheet_glyph &gl = glyph_of(fs, c);
        if (!gl.ok)
            continue;
        st.y0 = std::min(st.y0, y - gl.top);
        st.y1 = std::max(st.y1, y + gl.h - gl.top + 1);
        st.x0 = std::min(st.x0, x + gl.left);
        st.x1 = std::max(st.x1, x + gl.w + gl.left + 1);
        st.g.emplace_back(x, &gl);
        st.gy.push_back(y);
        st.any = true;
        x += gl.adv;
    }
    return st;
}

// The sheet: 8-bit RGB, top-down rows, stride 3 * w.
// Each row is held as the PNG encoder takes it (png_encode): a filter-type
// byte (0, None) then 3 * w bytes, so the buffer is deflated as it is,
// with no copy and no per-row call.
struct sheet_px {
    unsigned char *p;
    int w, h;
    size_t stride() const { return (size_t)w * 3 + 1; }
    unsigned char *at(int x, int y) const { return p + (size_t)y * stride() + 1 + (size_t)x * 3; }
};

struct clip {
    int x0, y0, x1, y1;   // exclusive ends
};

// ImageBufAlgo::render_text at pen (x, y), Left/Baseline: the glyphs written
// over one another into a zeroed alpha image of the string's box (a later
// glyph's blank pixels overwrite an earlier one's ink, as there), then
// every pixel of the box within the clip blended: a * colour + (1 - a) * pixel.
static void draw_text(const sheet_px &S, int x, int y, const std::string &t, int fs, const unsigned char col[3],
                      const clip &cl)
{
    sheet_text st = layout_text(t, fs);
    if (!st.any)
        return;
    const int bw = st.x1 - st.x0, bh = st.y1 - st.y0;
    thread_local std::vector<float> alpha;
    alpha.assign((size_t)bw * (size_t)bh, 0.0f);
    for (size_t k = 0; k < st.g.size(); k++) {
        const sheet_glyph &gl = *st.g[k].second;
        for (int j = 0; j < gl.h; j++) {
            int ry = st.gy[k] + j - gl.top - st.y0;
            float *dst = &alpha[(size_t)ry * (size_t)bw + (size_t)(st.g[k].first + gl.left - st.x0)];
            std::memcpy(dst, &gl.a[(size_t)j * (size_t)gl.w], (size_t)gl.w * sizeof(float));
        }
    }
    const float cf[3] = {u8_to_f(col[0]), u8_to_f(col[1]), u8_to_f(col[2])};
    const int X0 = std::max(x + st.x0, cl.x0), X1 = std::min(x + st.x1, cl.x1);
    const int Y0 = std::max(y + st.y0, cl.y0), Y1 = std::min(y + st.y1, cl.y1);
    for (int Y = Y0; Y < Y1; Y++) {
        const float *ar = &alpha[(size_t)(Y - y - st.y0) * (size_t)bw];
        for (int X = X0; X < X1; X++) {
            float a = ar[X - x - st.x0];
            if (a == 0.0f)
                continue;   // 0 * colour + 1 * pixel: the pixel as it was
            unsigned char *p = S.at(X, Y);
            for (int c = 0; c < 3; c++)
                p[c] = f_to_u8(a * cf[c] + (1.0f - a) * u8_to_f(p[c]));
        }
    }
}

// An opaque outline, x0..x1 and y0..y1 inclusive (render_box, fill off),
// within the clip.
static void draw_box(const sheet_px &S, int x0, int y0, int x1, int y1, const unsigned char col[3], const clip &cl)
{
    auto put = [&](int x, int y) {
        if (x >= cl.x0 && x < cl.x1 && y >= cl.y0 && y < cl.y1)
            std::memcpy(S.at(x, y), col, 3);
    };
    for (int x = std::min(x0, x1); x <= std::max(x0, x1); x++) {
        put(x, y0);
        put(x, y1);
    }
    for (int y = std::min(y0, y1); y <= std::max(y0, y1); y++) {
        put(x0, y);
        put(x1, y);
    }
}

// ---- the sheet's PNG ------------------------------------------------------
// Issue 20: OpenImageIO wrote the sheet through libpng and zlib, row by row
// (zlib level 3, the SUB filter): zlib's deflate and its adler32 were most
// of the writer thread's CPU. Here the sheet, already held row by row with
// its filter byte (None), is deflated in one call by libdeflate (a whole-
// buffer compressor: no sliding window to copy into, a vectorised adler32)
// and framed as the PNG specification's chunks: the signature, IHDR, the
// header OpenImageIO wrote (oFFs 0 0, then tEXt in the same order with the
// same keys), one IDAT, IEND, each with its CRC-32. The pixels are those
// OpenImageIO wrote; the file is smaller. Measured on the 240 sheets of the
// Moderno study decoded into memory, encode alone, CPU per sheet, two runs
// at load 3-8 (2 cores): libpng + zlib level 3, SUB (as OpenImageIO wrote
// them) 8.2-10.0 ms, 20.2 MB in all; zlib at levels 1-3 with any of None,
// Sub, Up, Paeth or Z_RLE 7.4-13.7 ms (Z_RLE 31-51 MB); libdeflate level 2,
// None 5.5-6.1 ms, 16.5 MB (level 1 10-12 ms, 3-4 5.6-7.4 ms, 6 7.7 ms for
// 13.4 MB; Sub and Up no faster). Level 2, None.
static const int sheet_deflate_level = 2;

static void put32(std::vector<unsigned char> &o, uint32_t v)
{
    const unsigned char b[4] = {(unsigned char)(v >> 24), (unsigned char)(v >> 16), (unsigned char)(v >> 8),
                                (unsigned char)v};
    o.insert(o.end(), b, b + 4);
}

// A chunk: length, type, data, and the CRC-32 of type and data.
static void png_chunk(std::vector<unsigned char> &o, const char type[4], const unsigned char *data, size_t n)
{
    put32(o, (uint32_t)n);
    const size_t at = o.size();
    o.insert(o.end(), type, type + 4);
    if (n)
        o.insert(o.end(), data, data + n);
    put32(o, libdeflate_crc32(0, o.data() + at, n + 4));
}

// The sheet S as a PNG (8-bit RGB, not interlaced) at tmp; on failure false
// and why. Keywords libpng would refuse (empty, over 79 bytes) are left out,
// as OpenImageIO's libpng left them.
static bool png_encode(const std::string &tmp, const sheet_px &S,
                       const std::vector<std::pair<std::string, std::string>> &text, std::string &why)
{
    // kept by the thread, like the sheet's pixels: a compressor holds ~1 MB
    // of tables, and fresh pages fault
    thread_local std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor *)> zc(
        nullptr, libdeflate_free_compressor);
    thread_local std::vector<unsigned char> o;
    // the deflated pixels, apart from o: growing a vector to the compressor's
    // bound zero-filled ~3.4 MB a sheet that the compressor then overwrote
    // (memset was 0.6% of the Moderno study's samples: issue 20)
    thread_local std::unique_ptr<unsigned char[]> z;
    thread_local size_t zcap = 0;
    if (!zc)
        zc.reset(libdeflate_alloc_compressor(sheet_deflate_level));
    if (!zc) {
        why = "no memory for the compressor";
        return false;
    }
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    o.assign(sig, sig + 8);
    unsigned char ihdr[13] = {0};
    for (int k = 0; k < 4; k++) {
        ihdr[k] = (unsigned char)((uint32_t)S.w >> (24 - 8 * k));
        ihdr[4 + k] = (unsigned char)((uint32_t)S.h >> (24 - 8 * k));
    }
    ihdr[8] = 8;   // bits per channel
    ihdr[9] = 2;   // RGB; compression, filter method and interlace 0
    png_chunk(o, "IHDR", ihdr, sizeof ihdr);
    const unsigned char offs[9] = {0};   // x = y = 0, in pixels
    png_chunk(o, "oFFs", offs, sizeof offs);
    std::string kv;
    for (const auto &t : text) {
        if (t.first.empty() || t.first.size() > 79)
            continue;
        kv = t.first;
        kv.push_back('\0');
        kv += t.second;
        png_chunk(o, "tEXt", (const unsigned char *)kv.data(), kv.size());
    }
    const size_t raw = S.stride() * (size_t)S.h, bound = libdeflate_zlib_compress_bound(zc.get(), raw);
    if (zcap < bound) {
        z.reset(new (std::nothrow) unsigned char[bound]);
        zcap = z ? bound : 0;
        if (!z) {
            why = "no memory for the compressed pixels";
            return false;
        }
    }
    const size_t n = libdeflate_zlib_compress(zc.get(), S.p, raw, z.get(), bound);
    if (n == 0) {
        why = "deflate";
        return false;
    }
    // the IDAT chunk around the compressed bytes: its length and type here,
    // the bytes from z, the CRC-32 of type and bytes after them
    put32(o, (uint32_t)n);
    o.insert(o.end(), {'I', 'D', 'A', 'T'});
    const uint32_t crc = libdeflate_crc32(libdeflate_crc32(0, "IDAT", 4), z.get(), n);
    std::vector<unsigned char> tail;
    put32(tail, crc);
    png_chunk(tail, "IEND", nullptr, 0);
    FILE *f = std::fopen(tmp.c_str(), "wb");
    if (!f) {
        why = tmp + ": " + std::strerror(errno);
        return false;
    }
    bool ok = std::fwrite(o.data(), 1, o.size(), f) == o.size() && std::fwrite(z.get(), 1, n, f) == n &&
              std::fwrite(tail.data(), 1, tail.size(), f) == tail.size();
    int err = ok ? 0 : errno;
    if (std::fclose(f) != 0 && ok) {
        ok = false;
        err = errno;
    }
    if (!ok)
        why = tmp + ": " + std::strerror(err);
    return ok;
}

static enum sl_err write_sheet(const char *path, const struct sl_image_sheet *s, struct sl_diag *d)
{
    const int W = s->w, H = s->h;
    // the caller's rows are bottom-up: frame row y (top-down) is rgb row H-1-y
    auto frame_at = [&](int x, int y) { return s->rgb + ((size_t)(H - 1 - y) * (size_t)W + (size_t)x) * 3; };
    int vx = 0, vy = 0, vw = W, vh = H;
    if (s->view[2] > 0) {
        vx = s->view[0];
        vw = s->view[2];
        vh = s->view[3];
        vy = H - (s->view[1] + vh);
    }
    const bool font = sheet_glyphs() != GLYPHS_NONE;
    std::unique_lock<std::mutex> lock(glyphs.mu);   // the glyph cache, held for the whole sheet
    // text about 1/48 of the frame's height (21 px at 1024), 12 to 22 px
    const int fs = std::clamp(std::max(vh, H) / 48, 12, 22);
    const int M = fs / 2 + 4, line = fs * 3 / 2;
    auto textw = [&](const std::string &t) {
        if (!font || t.empty())
            return 0;
        sheet_text st = layout_text(t, fs);
        return st.any ? st.x1 - st.x0 : 0;
    };
    static const unsigned char white[3] = {255, 255, 255}, black[3] = {0, 0, 0};
    const unsigned char rim[3] = {f_to_u8(0.55f), f_to_u8(0.55f), f_to_u8(0.55f)};

    // insets: nearest-neighbour zooms of their windows, each source pixel a
    // z x z square (what ImageBufAlgo::resample without interpolation gives
    // for an integer factor), cut from the frame before anything is marked
    // and drawn straight into the sheet below
    const int z = std::max(1, s->zoom), ni = std::clamp(s->ninsets, 0, SL_SHEET_MAX_INSETS);
    // window k in the frame's top-down pixels: x, y, w, h
    std::vector<std::array<int, 4>> win((size_t)ni);
    // laid out in columns beside the view, a new column when the next would
    // reach below the view (a short crop gets its insets side by side)
    std::vector<int> ix((size_t)ni), iy((size_t)ni);
    int colx = 0, colw = 0, cy = 0, colh = 0;
    for (int k = 0; k < ni; k++) {
        const int *b = s->inset[k];
        win[(size_t)k] = {b[0], H - (b[1] + b[3]), b[2], b[3]};
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
    // a white sheet with the view copied in row by row, in a buffer kept by
    // the thread and reused from sheet to sheet (fresh pages fault: issue 20)
    thread_local std::vector<unsigned char> pxv;
    const size_t rowb = (size_t)sw * 3;
    sheet_px S{nullptr, sw, sh};
    if (pxv.size() < S.stride() * (size_t)sh)
        pxv.resize(S.stride() * (size_t)sh);
    S.p = pxv.data();
    for (int j = 0; j < sh; j++) {
        unsigned char *r = S.at(0, j);
        r[-1] = 0;   // the row's PNG filter: None
        if (j < top || j >= top + vh) {
            std::memset(r, 255, rowb);
            continue;
        }
        std::memset(r, 255, (size_t)M * 3);
        std::memcpy(r + (size_t)M * 3, frame_at(vx, vy + (j - top)), (size_t)vw * 3);
        std::memset(r + (size_t)(M + vw) * 3, 255, rowb - (size_t)(M + vw) * 3);
    }
    const int ox = M - vx, oy = top - vy;   // frame (top-down) to sheet
    const clip all{0, 0, sw, sh}, vclip{M, top, M + vw, top + vh};

    // the windows marked on the view: a white 2-px box just outside each and
    // its number; then, inside the view, every error pixel put back as it
    // was, so a mark never covers one
    for (int k = 0; k < ni; k++) {
        const auto &r = win[(size_t)k];
        int x0 = r[0] + ox, y0 = r[1] + oy, x1 = r[0] + r[2] + ox, y1 = r[1] + r[3] + oy;
        draw_box(S, x0 - 2, y0 - 2, x1 + 1, y1 + 1, white, vclip);
        draw_box(S, x0 - 1, y0 - 1, x1, y1, white, vclip);
        if (font) {
            int ty = y0 - 4 - fs >= top ? y0 - 4 : y1 + 4 + fs;
            draw_text(S, x0 - 2, ty, std::to_string(k + 1), fs, white, vclip);
        }
        if (!s->keep)
            continue;
        const int ux0 = std::max(x0 - 3, vclip.x0), ux1 = std::min(x1 + 3 + fs, vclip.x1);
        const int uy0 = std::max(y0 - 8 - 2 * fs, vclip.y0), uy1 = std::min(y1 + 8 + 2 * fs, vclip.y1);
        for (int Y = uy0; Y < uy1; Y++) {
            const unsigned char *keep = s->keep + (size_t)(H - 1 - (Y - oy)) * (size_t)W;
            for (int X = ux0; X < ux1; X++)
                if (keep[X - ox])
                    std::memcpy(S.at(X, Y), frame_at(X - ox, Y - oy), 3);
        }
    }

    if (titleh)
        draw_text(S, M, M + fs, title, fs, black, all);
    std::string where[SL_SHEET_MAX_INSETS];
    for (int k = 0; k < ni; k++) {
        const auto &r = win[(size_t)k];
        int cx = M + vw + M + ix[(size_t)k], cy2 = top + iy[(size_t)k];
        if (font)
            draw_text(S, cx, cy2 + fs, s->inset_caption[k], fs, black, all);
        int py = cy2 + (font ? line : 0);
        const int zw = r[2] * z, zh = r[3] * z;
        // the inset's columns within the sheet; each source row is zoomed
        // once and its other z - 1 rows copied from it (a division and two
        // bounds tests per zoomed pixel were most of composing: issue 20)
        const int X0 = std::max(0, -cx), X1 = std::min(zw, sw - cx);
        const unsigned char *done = nullptr;   // the last zoomed row, in the sheet
        int done_src = -1;
        for (int Y = 0; Y < zh && X0 < X1; Y++) {
            if (py + Y < 0 || py + Y >= sh)
                continue;
            unsigned char *dst = S.at(0, py + Y) + (size_t)cx * 3;
            if (done && done_src == Y / z) {
                std::memcpy(dst + (size_t)X0 * 3, done + (size_t)X0 * 3, (size_t)(X1 - X0) * 3);
                continue;
            }
            const unsigned char *src = frame_at(r[0], r[1] + Y / z);
            for (int X = X0; X < X1;) {
                const unsigned char *p = src + (size_t)(X / z) * 3;
                for (const int end = std::min(X1, (X / z + 1) * z); X < end; X++)
                    std::memcpy(dst + (size_t)X * 3, p, 3);
            }
            done = dst;
            done_src = Y / z;
        }
        draw_box(S, cx - 1, py - 1, cx + zw, py + zh, rim, all);
        where[k] = std::to_string(r[0]) + " " + std::to_string(r[1]) + " " + std::to_string(r[2]) + " " +
                   std::to_string(r[3]) + " " + std::to_string(cx) + " " + std::to_string(py) + " " +
                   std::to_string(z);
    }
    std::string legend;
    for (size_t k = 0; k < lx.size(); k++) {
        const unsigned char *c = s->legend_rgb[k];
        // the swatch's colour through the float the fill was given
        const unsigned char cb[3] = {f_to_u8(c[0] / 255.0f), f_to_u8(c[1] / 255.0f), f_to_u8(c[2] / 255.0f)};
        int ex = lx[k], ey = legy + ly[k];
        for (int Y = std::max(ey, 0); Y < std::min(ey + fs, sh); Y++)
            for (int X = std::max(ex, 0); X < std::min(ex + fs, sw); X++)
                std::memcpy(S.at(X, Y), cb, 3);
        draw_box(S, ex, ey, ex + fs - 1, ey + fs - 1, black, all);
        if (font)
            draw_text(S, ex + fs + 6, ey + fs - fs / 5, s->legend_text[k], fs, black, all);
        legend += (k ? "; " : "") + std::string(s->legend_text[k]);
    }
    lock.unlock();

    // the header: what OpenImageIO wrote for these attributes, in this order
    std::vector<std::pair<std::string, std::string>> text;
    text.emplace_back("Software", std::string("shadowlab ") + module_sha);
    if (!title.empty())
        text.emplace_back("Description", title);   // OpenImageIO's name for ImageDescription
    text.emplace_back("shadowlab:view", std::to_string(vx) + " " + std::to_string(vy) + " " + std::to_string(vw) +
                                            " " + std::to_string(vh) + " " + std::to_string(M) + " " +
                                            std::to_string(top));
    for (int k = 0; k < ni; k++)
        text.emplace_back("shadowlab:inset" + std::to_string(k + 1), where[k]);
    text.emplace_back("shadowlab:legend", legend);
    text.emplace_back("shadowlab:text", font ? "1" : "0");
    for (int a = 0; a < s->nattrs; a++)
        text.emplace_back(s->attrs[a].name, s->attrs[a].value);
    std::string tmp = sl_image_tmp_name(path), why;
    if (!png_encode(tmp, S, text, why) || std::rename(tmp.c_str(), path) != 0) {
        if (why.empty())
            why = std::string("rename: ") + std::strerror(errno);
        std::remove(tmp.c_str());
        return sl_fail(d, SL_E_IMAGE, path, 0, NULL, "write failed: %s", why.c_str());
    }
    return SL_OK;
}

// One glyph as the sheet draws it (image.h), rendered afresh (uncached):
// the comparison of the two sources in overlay::glyphs_as_oiio.
static int sheet_glyph_fresh(int fs, uint32_t c, struct sl_image_glyph *g)
{
    std::memset(g, 0, sizeof *g);
    std::lock_guard<std::mutex> lock(glyphs.mu);
    const glyph_source src = sheet_glyphs();
    return src == GLYPHS_FREETYPE ? ft_glyph(fs, c, g) : src == GLYPHS_MODULE ? module_glyph(fs, c, g) : -1;
}

extern "C" __attribute__((visibility("default"))) const struct sl_sheet_ops *
sl_sheet_module(int abi, const char *git_sha, sl_image_glyph_fn glyph)
{
    static const struct sl_sheet_ops ops = {write_sheet, sheet_glyph_fresh};
    if (abi != SL_IMAGE_ABI)
        return NULL;
    module_sha = git_sha ? git_sha : "";
    module_glyph = glyph;
    return &ops;
}
