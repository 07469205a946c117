#include "method/neural/model_file.hpp"

#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"

namespace tcb::neural {

std::string ModelFile::preset() const {
  return trained.is_object() && trained.contains("preset") && trained["preset"].is_string()
             ? trained["preset"].get<std::string>()
             : std::string();
}

ModelFile read_model_file(const std::filesystem::path& path) {
  const std::string text = read_file(path);  // InputError: missing, a directory, unreadable
  try {
    const auto j = nlohmann::ordered_json::parse(text);
    return {Mlp<double>::from_json(j), j.is_object() && j.contains("trained") ? j["trained"] : nlohmann::ordered_json()};
  } catch (const std::exception& e) {
    throw InputError(path.string(), 0, e.what());
  }
}

}  // namespace tcb::neural
