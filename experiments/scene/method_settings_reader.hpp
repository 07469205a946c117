#pragma once
/// A method's settings read from a TOML table against the method's schema
/// (baselines/registry.hpp): each key typed and range-checked by the same
/// TableReader that reads scenes, sweeps and thresholds, so a bad value is an
/// InputError naming the file and line (or the --set that made it). Used for
/// a scene's [method.NAME] table and a sweep's { name = "NAME", ... } entry.

#include "baselines/registry.hpp"
#include "experiments/scene/toml_table_reader.hpp"

namespace tcb {

/// The schema's defaults overridden by the table's keys. Marks the schema's
/// keys as known to `reader`; the caller calls reader.finish() to reject the rest.
MethodSettings read_method_settings(TableReader& reader, const MethodInfo& method);

}  // namespace tcb
