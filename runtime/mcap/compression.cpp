#include "runtime/mcap/compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <memory>
#include <stdexcept>

#include "common/did_you_mean.hpp"
#include "runtime/base/error.hpp"

namespace robodds::mcap {
namespace {

// zstd level 1, its fastest regular level: the recorder must keep up with the bus on one core
// (throughput in docs/performance.md, "MCAP writer"; other levels were not measured).
constexpr int kZstdLevel = 1;

}  // namespace

Compression parse_compression(const std::string& text, const std::string& option_name) {
  if (text == "none") return Compression::kNone;
  if (text == "zstd") return Compression::kZstd;
  if (text == "lz4") return Compression::kLz4;
  throw ConfigError(option_name + ": unknown compression '" + text + "'" + did_you_mean(text, {"none", "zstd", "lz4"}) +
                    " (accepted: none, zstd, lz4)");
}

const char* record_name(Compression compression) {
  switch (compression) {
    case Compression::kZstd:
      return "zstd";
    case Compression::kLz4:
      return "lz4";
    case Compression::kNone:
      break;
  }
  return "";
}

const char* display_name(Compression compression) {
  return compression == Compression::kNone ? "none" : record_name(compression);
}

void compress_append(Compression compression, const void* data, std::size_t size, std::string& out) {
  const std::size_t start = out.size();
  switch (compression) {
    case Compression::kNone:
      out.append(static_cast<const char*>(data), size);
      return;
    case Compression::kZstd: {
      // One context per thread, reused: creating one per chunk costs more than compressing 1 MiB.
      thread_local std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> context(ZSTD_createCCtx(), &ZSTD_freeCCtx);
      out.resize(start + ZSTD_compressBound(size));
      const std::size_t n = ZSTD_compressCCtx(context.get(), out.data() + start, out.size() - start, data, size, kZstdLevel);
      if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
      out.resize(start + n);
      return;
    }
    case Compression::kLz4: {
      LZ4F_preferences_t preferences{};
      preferences.frameInfo.contentSize = size;  // lets readers size their buffer from the frame
      out.resize(start + LZ4F_compressFrameBound(size, &preferences));
      const std::size_t n = LZ4F_compressFrame(out.data() + start, out.size() - start, data, size, &preferences);
      if (LZ4F_isError(n)) throw std::runtime_error(std::string("lz4 compression failed: ") + LZ4F_getErrorName(n));
      out.resize(start + n);
      return;
    }
  }
}

bool decompress(const std::string& compression, const std::uint8_t* data, std::size_t size,
                std::uint64_t uncompressed_size, std::string& out, std::string& reason) {
  out.clear();
  if (compression.empty()) {
    if (size != uncompressed_size) {
      reason = "uncompressed chunk holds " + std::to_string(size) + " bytes, chunk says " + std::to_string(uncompressed_size);
      return false;
    }
    out.assign(reinterpret_cast<const char*>(data), size);
    return true;
  }
  // A corrupted size field must not make us allocate terabytes: no codec expands data more than
  // ~250x on data we write, and a bound keeps a hostile file from exhausting memory.
  if (uncompressed_size > std::uint64_t{size} * 1024 + 1024 * 1024) {
    reason = "chunk says " + std::to_string(uncompressed_size) + " uncompressed bytes from " + std::to_string(size) +
             " compressed: implausible";
    return false;
  }
  out.resize(static_cast<std::size_t>(uncompressed_size));
  if (compression == "zstd") {
    const std::size_t n = ZSTD_decompress(out.data(), out.size(), data, size);
    if (ZSTD_isError(n)) {
      reason = std::string("zstd: ") + ZSTD_getErrorName(n);
      return false;
    }
    if (n != uncompressed_size) {
      reason = "zstd: decompressed to " + std::to_string(n) + " bytes, chunk says " + std::to_string(uncompressed_size);
      return false;
    }
    return true;
  }
  if (compression == "lz4") {
    LZ4F_dctx* context = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION))) {
      reason = "lz4: cannot create a decompression context";
      return false;
    }
    std::size_t in_pos = 0;
    std::size_t out_pos = 0;
    std::size_t status = 1;
    while (status != 0 && in_pos < size) {
      std::size_t in_n = size - in_pos;
      std::size_t out_n = out.size() - out_pos;
      status = LZ4F_decompress(context, out.data() + out_pos, &out_n, data + in_pos, &in_n, nullptr);
      if (LZ4F_isError(status)) break;
      in_pos += in_n;
      out_pos += out_n;
      if (in_n == 0 && out_n == 0) break;  // no progress: output full or input exhausted
    }
    LZ4F_freeDecompressionContext(context);
    if (LZ4F_isError(status)) {
      reason = std::string("lz4: ") + LZ4F_getErrorName(status);
      return false;
    }
    if (status != 0 || out_pos != uncompressed_size) {
      reason = "lz4: decompressed to " + std::to_string(out_pos) + " bytes (frame " +
               (status == 0 ? "complete" : "incomplete") + "), chunk says " + std::to_string(uncompressed_size);
      return false;
    }
    return true;
  }
  reason = "unknown compression '" + compression + "' (known: zstd, lz4, none)";
  return false;
}

}  // namespace robodds::mcap
