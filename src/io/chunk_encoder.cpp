#include "chunk_encoder.hpp"

#include <libdeflate.h>

#include <new>

namespace avalanche::detail {

ChunkEncoder::ChunkEncoder(int level) : compressor_(libdeflate_alloc_compressor(level)) {
    if (compressor_ == nullptr) throw std::bad_alloc();
}

ChunkEncoder::~ChunkEncoder() { libdeflate_free_compressor(compressor_); }

std::size_t ChunkEncoder::prepare(std::size_t n) {
    shuffled_.resize(n * sizeof(double));
    return libdeflate_zlib_compress_bound(compressor_, n * sizeof(double));
}

void ChunkEncoder::encode(const double* values, std::size_t n, std::vector<unsigned char>& out) {
    constexpr std::size_t kBytes = sizeof(double);
    const std::size_t size = n * kBytes;
    shuffled_.resize(size);
    // H5Z_filter_shuffle: output byte k * n + i is byte k of value i.
    const auto* in = reinterpret_cast<const unsigned char*>(values);
    for (std::size_t k = 0; k < kBytes; ++k) {
        unsigned char* plane = shuffled_.data() + k * n;
        for (std::size_t i = 0; i < n; ++i) plane[i] = in[i * kBytes + k];
    }
    out.resize(libdeflate_zlib_compress_bound(compressor_, size));
    // Never 0 here: the buffer holds the compressor's bound for this size.
    const std::size_t written = libdeflate_zlib_compress(compressor_, shuffled_.data(), size, out.data(), out.size());
    out.resize(written);
}

}  // namespace avalanche::detail
