#pragma once
// Shared by the SEG-Y reader (segy*.cpp) and writer (segy_writer.cpp): an owning segyio handle,
// readable names for segyio's status codes, and the marks geotandem leaves in the textual header.

#include <segyio/segy.h>

#include <memory>
#include <string>

namespace geotandem::volume::detail::segy {

struct Closer {
  void operator()(segy_file* file) const noexcept {
    if (file) segy_close(file);
  }
};
// Closes on destruction, ignoring errors: a writer that must know whether the final flush worked
// calls close() below instead.
using Handle = std::unique_ptr<segy_file, Closer>;

// Closes and reports segyio's status (0 on success).
inline int close(Handle& handle) {
  return handle ? segy_close(handle.release()) : 0;
}

inline std::string status_text(int code) {
  switch (code) {
  case SEGY_OK: return "ok";
  case SEGY_FOPEN_ERROR: return "cannot open the file";
  case SEGY_FSEEK_ERROR: return "seek failed";
  case SEGY_FREAD_ERROR: return "read failed (file shorter than its headers say?)";
  case SEGY_FWRITE_ERROR: return "write failed (disk full?)";
  case SEGY_INVALID_FIELD: return "invalid header field";
  case SEGY_INVALID_SORTING: return "traces are neither inline- nor crossline-sorted";
  case SEGY_MISSING_LINE_INDEX: return "a line index is missing";
  case SEGY_INVALID_OFFSETS: return "inconsistent offsets";
  case SEGY_TRACE_SIZE_MISMATCH: return "the file size is not a whole number of traces";
  case SEGY_INVALID_ARGS: return "invalid arguments";
  default: return "segyio status " + std::to_string(code);
  }
}

// Byte positions (1-based, as in the standard) of the header fields geotandem reads and writes.
inline constexpr int kInlineField = SEGY_TR_INLINE;       // 189
inline constexpr int kCrosslineField = SEGY_TR_CROSSLINE; // 193
inline constexpr int kOffsetField = SEGY_TR_OFFSET;       // 37

// The textual header geotandem writes begins with this word; only then does the reader trust the
// sample-axis line below (SEG-Y rev 1 has no binary field saying "depth").
inline constexpr const char* kMark = "GEOTANDEM";
// Present in that header when the sample axis is depth in metres, stored in the interval field
// in millimetres (the field normally holds microseconds).
inline constexpr const char* kDepthMark = "SAMPLE AXIS: DEPTH";

} // namespace geotandem::volume::detail::segy
