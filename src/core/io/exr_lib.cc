// exr_lib.cc: OpenEXR files decoded from memory with the OpenEXR library's
// C++ API (InputFile over an in-memory IStream), for vx_exr_read_mem
// (exr.c).  The library's C API (OpenEXRCore) of Debian 12's version 3.1
// cannot decompress DWAA/DWAB, which Blender's environments use.
// Everything here but vx_exr_decode has internal linkage.
#include "exr_priv.h"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <Iex.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>

namespace {

// MemStream: the file's bytes, copied out on each read.  Not offered as
// memory-mapped: the library (3.1) then decodes a chunk in place and, for
// an uncompressed chunk shorter than its data window says, reads past it;
// copied, the chunk lies in the library's own buffer of the full size.
class MemStream : public Imf::IStream {
public:
	MemStream(const char *p, size_t n)
	    : Imf::IStream("<memory>"), p_(p), n_(n), pos_(0) {}

	bool read(char c[], int k) override
	{
		need(k);
		if (k > 0)
			std::memcpy(c, p_ + pos_, (size_t)k);
		pos_ += (uint64_t)k;
		return pos_ < n_;
	}

	uint64_t tellg() override { return pos_; }

	// A position past the end is kept: the next read fails.
	void seekg(uint64_t pos) override { pos_ = pos; }

private:
	void need(int k)
	{
		if (k < 0 || pos_ > n_ || (uint64_t)k > n_ - pos_)
			throw Iex::InputExc("unexpected end of file (truncated)");
	}

	const char *p_;
	uint64_t n_, pos_;
};

// say: msg gets "exr: " and what, control characters made blanks.
void
say(char *msg, size_t cap, const char *what)
{
	if (cap == 0)
		return;
	std::snprintf(msg, cap, "exr: %s", what);
	for (char *q = msg; *q != '\0'; q++)
		if ((unsigned char)*q < 0x20 || *q == 0x7f)
			*q = ' ';
}

// wsize: a window's width and height, 0 when empty or beyond the limits.
bool
wsize(const Imath::Box2i &b, int maxdim, size_t maxpix, int *w, int *h)
{
	int64_t ww = (int64_t)b.max.x - b.min.x + 1;
	int64_t hh = (int64_t)b.max.y - b.min.y + 1;

	if (ww < 1 || hh < 1 || ww > maxdim || hh > maxdim ||
	    (uint64_t)ww * (uint64_t)hh > maxpix)
		return false;
	*w = (int)ww;
	*h = (int)hh;
	return true;
}

int
decode(const void *buf, size_t n, int maxdim, size_t maxpix,
    vx_exr_alloc_fn alloc, void *ctx, char *msg, size_t cap)
{
	Imf::Header::setMaxImageSize(maxdim, maxdim);
	Imf::Header::setMaxTileSize(maxdim, maxdim);
	MemStream st((const char *)buf, n);
	Imf::InputFile in(st, 0);
	const Imf::Header &hd = in.header();
	const Imath::Box2i dw = hd.dataWindow(), dp = hd.displayWindow();
	const Imf::ChannelList &cl = hd.channels();
	const char *names[3] = { "R", "G", "B" };
	int dww, dwh, w, h, gray;
	char m[160];

	if (!wsize(dw, maxdim, maxpix, &dww, &dwh) ||
	    !wsize(dp, maxdim, maxpix, &w, &h)) {
		std::snprintf(m, sizeof m, "data window (%d,%d)-(%d,%d) or "
		    "display window (%d,%d)-(%d,%d): size beyond the limits (1 "
		    "to %d a side, at most %zu pixels)", dw.min.x, dw.min.y,
		    dw.max.x, dw.max.y, dp.min.x, dp.min.y, dp.max.x, dp.max.y,
		    maxdim, maxpix);
		say(msg, cap, m);
		return 65;
	}
	if (cl.findChannel("RY") != nullptr || cl.findChannel("BY") != nullptr) {
		say(msg, cap, "luminance-chroma (RY, BY) images are not read");
		return 65;
	}
	gray = cl.findChannel("R") == nullptr && cl.findChannel("G") == nullptr &&
	    cl.findChannel("B") == nullptr && cl.findChannel("Y") != nullptr;
	if (gray)
		names[0] = "Y";
	for (int c = 0; c < (gray ? 1 : 3); c++) {
		const Imf::Channel *ch = cl.findChannel(names[c]);

		if (ch == nullptr) {
			std::snprintf(m, sizeof m, "no channel %s (R, G and B, or "
			    "Y alone, are read)", names[c]);
			say(msg, cap, m);
			return 65;
		}
		if (ch->xSampling != 1 || ch->ySampling != 1) {
			std::snprintf(m, sizeof m, "channel %s is subsampled "
			    "(%d x %d)", names[c], ch->xSampling, ch->ySampling);
			say(msg, cap, m);
			return 65;
		}
	}

	float *out = alloc(ctx, w, h), *tmp = nullptr, *dst;
	if (out == nullptr)
		return 70;
	if (dw == dp) {
		dst = out;
	} else {
		tmp = (float *)std::calloc((size_t)dww * (size_t)dwh * 3,
		    sizeof(float));
		if (tmp == nullptr)
			throw std::bad_alloc();
		dst = tmp;
	}

	const size_t xs = 3 * sizeof(float), ys = xs * (size_t)dww;
	Imf::FrameBuffer fb;
	for (int c = 0; c < (gray ? 1 : 3); c++)
		fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, dst + c, dw, xs,
		    ys));
	try {
		in.setFrameBuffer(fb);
		in.readPixels(dw.min.y, dw.max.y);
	} catch (...) {
		std::free(tmp);
		throw;
	}
	if (tmp != nullptr) {
		int x0 = dw.min.x > dp.min.x ? dw.min.x : dp.min.x;
		int x1 = dw.max.x < dp.max.x ? dw.max.x : dp.max.x;
		int y0 = dw.min.y > dp.min.y ? dw.min.y : dp.min.y;
		int y1 = dw.max.y < dp.max.y ? dw.max.y : dp.max.y;

		for (int y = y0; y <= y1 && x0 <= x1; y++)
			std::memcpy(out + 3 * ((size_t)(y - dp.min.y) * (size_t)w +
			    (size_t)(x0 - dp.min.x)), tmp + 3 * ((size_t)(y -
			    dw.min.y) * (size_t)dww + (size_t)(x0 - dw.min.x)),
			    3 * sizeof(float) * (size_t)(x1 - x0 + 1));
		std::free(tmp);
	}
	if (gray)
		for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
			out[3 * i + 1] = out[3 * i + 2] = out[3 * i];
	return 0;
}

} // namespace

extern "C" int
vx_exr_decode(const void *buf, size_t n, int maxdim, size_t maxpix,
    vx_exr_alloc_fn alloc, void *ctx, char *msg, size_t msgcap)
{
	try {
		return decode(buf, n, maxdim, maxpix, alloc, ctx, msg, msgcap);
	} catch (const std::bad_alloc &) {
		say(msg, msgcap, "out of memory");
		return 71;
	} catch (const std::exception &x) {
		say(msg, msgcap, x.what());
		return 65;
	} catch (...) {
		say(msg, msgcap, "the OpenEXR library failed");
		return 65;
	}
}
