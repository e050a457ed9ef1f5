/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    RGB raster and minimal PNG encoder (see iceFieldImage.H).
\*---------------------------------------------------------------------------*/

#include "iceFieldImage.H"

#include <algorithm>
#include <cmath>
#include <fstream>

namespace iceDEM
{

// * * * * * * * * * * * * * * * Checksums * * * * * * * * * * * * * * * * //

std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc)
{
    // Table of the reflected polynomial 0xEDB88320, built once
    static const std::array<std::uint32_t, 256> table = []
    {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t k = 0; k < 256; ++k)
        {
            std::uint32_t c = k;
            for (int b = 0; b < 8; ++b)
            {
                c = (c & 1u) ? (0xEDB88320u ^ (c >> 1)) : (c >> 1);
            }
            t[k] = c;
        }
        return t;
    }();

    crc = ~crc;
    for (std::size_t i = 0; i < n; ++i)
    {
        crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
    }
    return ~crc;
}


std::uint32_t adler32(const std::uint8_t* data, std::size_t n)
{
    const std::uint32_t mod = 65521u;
    std::uint32_t a = 1;
    std::uint32_t b = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
        a = (a + data[i]) % mod;
        b = (b + a) % mod;
    }
    return (b << 16) | a;
}


namespace
{

void putBE32(std::vector<std::uint8_t>& out, std::uint32_t v)
{
    out.push_back(std::uint8_t(v >> 24));
    out.push_back(std::uint8_t(v >> 16));
    out.push_back(std::uint8_t(v >> 8));
    out.push_back(std::uint8_t(v));
}

//- Append a PNG chunk: length, type, data, CRC of type + data
void putChunk
(
    std::vector<std::uint8_t>& out,
    const char type[4],
    const std::vector<std::uint8_t>& data
)
{
    putBE32(out, std::uint32_t(data.size()));
    std::vector<std::uint8_t> body(type, type + 4);
    body.insert(body.end(), data.begin(), data.end());
    out.insert(out.end(), body.begin(), body.end());
    putBE32(out, crc32(body.data(), body.size()));
}

} // anonymous namespace


// * * * * * * * * * * * * * * * * RgbImage  * * * * * * * * * * * * * * * //

RgbImage::RgbImage
(
    int width,
    double x0,
    double x1,
    double y0,
    double y1,
    const Rgb& background
)
:
    width_(std::max(1, width)),
    height_(1),
    x0_(x0),
    y0_(y0),
    scale_(1)
{
    const double l = std::max(x1 - x0, 1e-300);
    scale_ = width_/l;
    height_ = std::max(1, int(std::lround((y1 - y0)*scale_)));
    data_.resize(std::size_t(width_)*height_*3);
    for (std::size_t p = 0; p < data_.size(); p += 3)
    {
        data_[p] = background[0];
        data_[p + 1] = background[1];
        data_[p + 2] = background[2];
    }
}


void RgbImage::set(int i, int j, const Rgb& c)
{
    if (i < 0 || j < 0 || i >= width_ || j >= height_)
    {
        return;
    }
    const std::size_t p = (std::size_t(j)*width_ + i)*3;
    data_[p] = c[0];
    data_[p + 1] = c[1];
    data_[p + 2] = c[2];
}


Rgb RgbImage::get(int i, int j) const
{
    const std::size_t p = (std::size_t(j)*width_ + i)*3;
    return {data_[p], data_[p + 1], data_[p + 2]};
}


void RgbImage::fillConvexPolygon
(
    const std::vector<Vec2>& polygon,
    const Rgb& c
)
{
    const std::size_t n = polygon.size();
    if (n < 3)
    {
        return;
    }
    // Pixel coordinates: u = (x - x0) s, v = height - (y - y0) s
    std::vector<Vec2> q(n);
    double vMin = 1e300;
    double vMax = -1e300;
    for (std::size_t k = 0; k < n; ++k)
    {
        q[k] = Vec2
        (
            (polygon[k].x() - x0_)*scale_,
            height_ - (polygon[k].y() - y0_)*scale_
        );
        vMin = std::min(vMin, q[k].y());
        vMax = std::max(vMax, q[k].y());
    }
    const int j0 = std::max(0, int(std::floor(vMin - 0.5)));
    const int j1 = std::min(height_ - 1, int(std::ceil(vMax - 0.5)));
    for (int j = j0; j <= j1; ++j)
    {
        const double v = j + 0.5;
        double uMin = 1e300;
        double uMax = -1e300;
        for (std::size_t k = 0; k < n; ++k)
        {
            const Vec2& a = q[k];
            const Vec2& b = q[(k + 1) % n];
            if ((a.y() <= v) != (b.y() <= v))
            {
                const double u = a.x() + (v - a.y())*(b.x() - a.x())/(b.y() - a.y());
                uMin = std::min(uMin, u);
                uMax = std::max(uMax, u);
            }
        }
        if (uMax < uMin)
        {
            continue;
        }
        const int i0 = std::max(0, int(std::ceil(uMin - 0.5)));
        const int i1 = std::min(width_ - 1, int(std::floor(uMax - 0.5)));
        for (int i = i0; i <= i1; ++i)
        {
            set(i, j, c);
        }
    }
}


void RgbImage::drawLine
(
    const Vec2& a,
    const Vec2& b,
    const Rgb& c,
    int thickness
)
{
    const double ua = (a.x() - x0_)*scale_;
    const double va = height_ - (a.y() - y0_)*scale_;
    const double ub = (b.x() - x0_)*scale_;
    const double vb = height_ - (b.y() - y0_)*scale_;
    const double len = std::max(std::abs(ub - ua), std::abs(vb - va));
    const int steps = std::max(1, int(std::ceil(2*len)));
    const int h = std::max(1, thickness);
    const int lo = -(h - 1)/2;
    for (int s = 0; s <= steps; ++s)
    {
        const double t = double(s)/steps;
        const int i = int(std::floor(ua + t*(ub - ua)));
        const int j = int(std::floor(va + t*(vb - va)));
        for (int di = lo; di < lo + h; ++di)
        {
            for (int dj = lo; dj < lo + h; ++dj)
            {
                set(i + di, j + dj, c);
            }
        }
    }
}


void RgbImage::drawPolygon
(
    const std::vector<Vec2>& polygon,
    const Rgb& c,
    int thickness
)
{
    const std::size_t n = polygon.size();
    for (std::size_t k = 0; k < n; ++k)
    {
        drawLine(polygon[k], polygon[(k + 1) % n], c, thickness);
    }
}


void RgbImage::drawCircle
(
    const Vec2& centre,
    double radius,
    const Rgb& c,
    int thickness
)
{
    const double twoPi = 2*std::acos(-1.0);
    const double rPix = radius*scale_;
    const int n = std::max(8, int(std::ceil(2*twoPi*rPix)));
    std::vector<Vec2> p(n);
    for (int k = 0; k < n; ++k)
    {
        const double t = twoPi*k/n;
        p[k] = centre + radius*Vec2(std::cos(t), std::sin(t));
    }
    drawPolygon(p, c, thickness);
}


bool RgbImage::writePng(const std::string& fileName) const
{
    std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

    // IHDR
    {
        std::vector<std::uint8_t> d;
        putBE32(d, std::uint32_t(width_));
        putBE32(d, std::uint32_t(height_));
        d.push_back(8);     // bit depth
        d.push_back(2);     // colour type: RGB
        d.push_back(0);     // compression: deflate
        d.push_back(0);     // filter method
        d.push_back(0);     // no interlace
        putChunk(png, "IHDR", d);
    }

    // Raw scanlines, each led by filter type 0
    const std::size_t rowBytes = std::size_t(width_)*3;
    std::vector<std::uint8_t> raw;
    raw.reserve((rowBytes + 1)*height_);
    for (int j = 0; j < height_; ++j)
    {
        raw.push_back(0);
        const auto row = data_.begin() + std::ptrdiff_t(j*rowBytes);
        raw.insert(raw.end(), row, row + std::ptrdiff_t(rowBytes));
    }

    // zlib: header (deflate, 32K window, no dictionary, check bits), stored
    // blocks, Adler-32
    {
        std::vector<std::uint8_t> z{0x78, 0x01};
        const std::size_t maxBlock = 65535;
        std::size_t pos = 0;
        do
        {
            const std::size_t len = std::min(maxBlock, raw.size() - pos);
            const bool last = (pos + len == raw.size());
            z.push_back(last ? 1 : 0);      // BFINAL, BTYPE = 00 (stored)
            z.push_back(std::uint8_t(len & 0xFFu));
            z.push_back(std::uint8_t(len >> 8));
            z.push_back(std::uint8_t(~len & 0xFFu));
            z.push_back(std::uint8_t((~len >> 8) & 0xFFu));
            z.insert
            (
                z.end(),
                raw.begin() + std::ptrdiff_t(pos),
                raw.begin() + std::ptrdiff_t(pos + len)
            );
            pos += len;
        } while (pos < raw.size());
        putBE32(z, adler32(raw.data(), raw.size()));
        putChunk(png, "IDAT", z);
    }

    putChunk(png, "IEND", {});

    std::ofstream os(fileName, std::ios::binary);
    if (!os)
    {
        return false;
    }
    os.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    return bool(os);
}


} // namespace iceDEM
