#pragma once
// One chunk of a dataset stored with HDF5's shuffle and deflate filters, encoded here
// instead of in HDF5's filter pipeline: the chunks of a snapshot are then compressed on
// the run's threads at once, and H5Dwrite_chunk stores the bytes as they are (HDF5's
// pipeline compresses one chunk after the other, on one thread; it was 13 % of the time
// loop of a whole avaKot run at 5 m on two threads, docs/performance.md). A reader
// decodes the chunks with the dataset's filters, as any other.
#include <cstddef>
#include <vector>

struct libdeflate_compressor;

namespace avalanche::detail {

class ChunkEncoder {
  public:
    // `level`: the deflate level (1 fastest .. 12 smallest; libdeflate's scale).
    explicit ChunkEncoder(int level);
    ~ChunkEncoder();
    ChunkEncoder(const ChunkEncoder&) = delete;
    ChunkEncoder& operator=(const ChunkEncoder&) = delete;

    // Sizes the encoder's buffer for chunks of `n` doubles and returns the most bytes
    // encode() can give for them, so that encoding allocates nothing (it runs in an
    // OpenMP region, which an exception must not leave).
    std::size_t prepare(std::size_t n);

    // The bytes HDF5 stores for `n` doubles under its shuffle filter (element size 8:
    // byte k of every value, k = 0..7, one plane after the other) followed by its
    // deflate filter (a zlib stream, RFC 1950). Replaces the contents of `out`, which
    // must hold prepare(n) bytes of capacity to be filled without allocating.
    void encode(const double* values, std::size_t n, std::vector<unsigned char>& out);

  private:
    libdeflate_compressor* compressor_ = nullptr;
    std::vector<unsigned char> shuffled_;
};

}  // namespace avalanche::detail
