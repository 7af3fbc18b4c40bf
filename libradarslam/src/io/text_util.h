#pragma once
// Small text helpers shared by the dataset readers: line-by-line reading, CSV splitting and
// number parsing that turn every malformed field into an InputError naming the file and line.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

#include "radarslam/core/time.h"

namespace radarslam::io_detail {

/// Opens a text file for reading or throws InputError(path, "cannot open ...").
std::ifstream openText(const std::filesystem::path& path, const char* what);

/// Splits on `sep`, trimming spaces, tabs and a trailing '\r' from every field.
std::vector<std::string_view> split(std::string_view line, char sep);

std::string_view trim(std::string_view s);

/// "file:line" style location for messages about a line of a text file.
std::string lineWhere(const std::filesystem::path& file, std::size_t line_no);

/// A non-blank line of a text file, split into fields (valid during the callback only).
struct DataLine {
  std::size_t number = 0;                ///< 1-based line number
  std::string where;                     ///< "file:line", for messages
  std::vector<std::string_view> fields;  ///< the trimmed line split on the separator
};

/// Reads `in` to its end and calls f(const DataLine&) for every non-blank line; `lines_read` lines
/// (e.g. a header) were consumed before, so numbers continue from there.
template <class F>
void forEachDataLine(std::istream& in, const std::filesystem::path& file, char sep, std::size_t lines_read,
                     F&& f) {
  std::string line;
  DataLine d;
  d.number = lines_read;
  while (std::getline(in, line)) {
    ++d.number;
    if (trim(line).empty()) continue;
    d.where = lineWhere(file, d.number);
    d.fields = split(trim(line), sep);
    f(static_cast<const DataLine&>(d));
  }
}

/// Parse helpers: throw InputError(where, "<field name> is not a number: '<text>'").
double parseDouble(std::string_view text, const std::string& where, const char* field);
std::int64_t parseInt(std::string_view text, const std::string& where, const char* field);
/// An integer count of microseconds as ns; throws like parseInt, and if the ns count overflows.
StampNs parseMicroseconds(std::string_view text, const std::string& where, const char* field);
/// A UNIX timestamp whose unit is given by its digit count (see parseStampByDigits).
StampNs parseStamp(std::string_view text, const std::string& where, const char* field);

/// Reads a whole binary file; throws InputError if it cannot be read.
std::vector<unsigned char> readBytes(const std::filesystem::path& path);

}  // namespace radarslam::io_detail
