// A CSV file read for its numbers: the header's names, the rows' cells as
// text, and each row's line in the file, so that a bad cell is reported
// where it is.
//
// Lines that start with '#' are comments (a data set's source and units,
// as ../shared/data's files and assets/ carry them); blank lines are
// skipped. Cells are separated by commas, without quoting: the files the
// program writes and reads back never quote. A row with a different count
// of cells than the header is refused with its line.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace simsols {

struct CsvTable {
  std::string source;  // the file's name in messages
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> lines;  // each row's line in the file (1-based)

  // The column called `name`; -1 when there is none.
  int column(std::string_view name) const;
  // The header's names joined by ", " (for "allowed: ..." messages).
  std::string names() const;
  // Row r's cell in column c as a number; ReadError naming the source, the
  // line and the column when it is not one.
  double number(std::size_t r, int c) const;
};

// ReadError naming `source` when a row's cell count differs from the
// header's, or when there is no header.
CsvTable parse_csv(std::string_view text, const std::string& source);
// The file at `path` (ReadError when it cannot be read), as parse_csv.
CsvTable read_csv(const std::string& path);

}  // namespace simsols
