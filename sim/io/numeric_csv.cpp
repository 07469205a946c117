#include "sim/io/numeric_csv.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "sim/io/input_error.hpp"

namespace tcb {

std::vector<std::vector<double>> read_numeric_csv(const std::filesystem::path& path, const std::string& header,
                                                  const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path.string(), 0, "is a directory, not a " + what + " file");
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), 0, "cannot open the " + what + " file");
  const std::size_t width = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
  const std::string count = std::to_string(width) + " values";
  std::vector<std::vector<double>> rows;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      if (line != header) throw InputError(path.string(), 1, "expected the header " + header);
      continue;
    }
    if (line.empty()) continue;
    std::stringstream cells(line);
    std::vector<double> row(width);
    for (std::size_t k = 0; k < width; ++k) {
      std::string cell;
      if (!std::getline(cells, cell, ',')) throw InputError(path.string(), number, "expected " + count);
      try {
        std::size_t used = 0;
        row[k] = std::stod(cell, &used);
        if (used != cell.size()) throw std::invalid_argument(cell);
      } catch (const std::exception&) {
        throw InputError(path.string(), number, "'" + cell + "' is not a number");
      }
      if (!std::isfinite(row[k])) throw InputError(path.string(), number, "values must be finite");
    }
    std::string extra;
    if (std::getline(cells, extra, ',')) throw InputError(path.string(), number, "expected " + count);
    if (!rows.empty() && !(row[0] > rows.back()[0])) throw InputError(path.string(), number, "times must increase strictly");
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw InputError(path.string(), number, "no samples");
  return rows;
}

}  // namespace tcb
