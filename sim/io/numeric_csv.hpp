#pragma once
/// A small CSV of numbers with a fixed header, as the driven objects' paths
/// use (world/trajectory.hpp, latent/latent_path.hpp): the first line must be
/// exactly `header`; every other non-empty line holds exactly as many
/// comma-separated finite numbers as the header has names; the first column
/// (time) increases strictly. A trailing CR is ignored. Anything else is an
/// InputError naming the file and the line, and `what` ("trajectory") says
/// which kind of file could not be opened.

#include <filesystem>
#include <string>
#include <vector>

namespace tcb {

/// The rows, each header-width long; at least one.
std::vector<std::vector<double>> read_numeric_csv(const std::filesystem::path& path, const std::string& header,
                                                  const std::string& what);

}  // namespace tcb
