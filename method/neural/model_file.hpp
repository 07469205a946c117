#pragma once
/// A detector as `tcbench neural train` writes it: the network's
/// tcbench-mlp-1 JSON (mlp.hpp) plus an optional "trained" object saying how
/// it was made (its "preset" names the latent family it was trained for).
/// read_model_file throws InputError naming the file and the problem once
/// (a missing file, bad JSON, a malformed network).

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "method/neural/mlp.hpp"

namespace tcb::neural {

struct ModelFile {
  Mlp<double> net;
  nlohmann::ordered_json trained;  ///< null when the file has none
  /// trained.preset, or empty.
  std::string preset() const;
};

ModelFile read_model_file(const std::filesystem::path& path);

}  // namespace tcb::neural
