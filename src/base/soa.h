// Structure-of-arrays storage for per-particle and per-spring vectors and
// symmetric 3x3 blocks. The hot loops read and write plain float arrays so
// the compiler vectorizes them; get/set convert to Eigen at the edges.
#pragma once

#include <algorithm>

#include "base/host_allocator.h"
#include "base/math.h"

namespace cloth {

struct Vec3Soa {
    explicit Vec3Soa(const HostMemory* memory)
        : x(HostAllocator<float>(memory)), y(HostAllocator<float>(memory)), z(HostAllocator<float>(memory)) {}

    HostVector<float> x, y, z;

    size_t size() const { return x.size(); }
    void resize(size_t n) {
        x.resize(n);
        y.resize(n);
        z.resize(n);
    }
    // Exchanges the buffers with other's (no copy).
    void swap_buffers(Vec3Soa& other) {
        x.swap(other.x);
        y.swap(other.y);
        z.swap(other.z);
    }
    void fill(const Vec3& value) {
        std::fill(x.begin(), x.end(), value.x());
        std::fill(y.begin(), y.end(), value.y());
        std::fill(z.begin(), z.end(), value.z());
    }
    Vec3 get(size_t i) const { return {x[i], y[i], z[i]}; }
    void set(size_t i, const Vec3& v) {
        x[i] = v.x();
        y[i] = v.y();
        z[i] = v.z();
    }
};

struct Sym3Soa {
    explicit Sym3Soa(const HostMemory* memory)
        : xx(HostAllocator<float>(memory)),
          xy(HostAllocator<float>(memory)),
          xz(HostAllocator<float>(memory)),
          yy(HostAllocator<float>(memory)),
          yz(HostAllocator<float>(memory)),
          zz(HostAllocator<float>(memory)) {}

    HostVector<float> xx, xy, xz, yy, yz, zz;

    size_t size() const { return xx.size(); }
    void resize(size_t n) {
        for (HostVector<float>* a : {&xx, &xy, &xz, &yy, &yz, &zz}) a->resize(n);
    }
    Sym3 get(size_t i) const { return {xx[i], xy[i], xz[i], yy[i], yz[i], zz[i]}; }
    void set(size_t i, const Sym3& m) {
        xx[i] = m.xx;
        xy[i] = m.xy;
        xz[i] = m.xz;
        yy[i] = m.yy;
        yz[i] = m.yz;
        zz[i] = m.zz;
    }
};

}  // namespace cloth
