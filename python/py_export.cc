#include "python/py_export.h"

#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "driver/relight/tree_export.h"
#include "python/py_convert.h"

namespace wavebake::python {
namespace {

namespace py = pybind11;

// The command line's rules (cli/cmd_export.cc) for what CLI11 checks there:
// one format, a cut-off or a target error, not both; the runtime checks
// their values (bits, finiteness) and names them.
// bits: None or "auto" (the default per-level rule), an int (every level)
// or a sequence of ints (one per level, level 0 first).
std::vector<int> CodeBits(const py::object& bits) {
  if (bits.is_none()) return {};
  if (py::isinstance<py::str>(bits)) {
    absl::StatusOr<std::vector<int>> parsed = ParseCodeBits(bits.cast<std::string>());
    if (!parsed.ok()) RaiseInvalid(std::string(parsed.status().message()));
    return *parsed;
  }
  if (py::isinstance<py::bool_>(bits)) RaiseInvalid("bits: not a number of bits");
  if (py::isinstance<py::int_>(bits)) return {bits.cast<int>()};
  try {
    return bits.cast<std::vector<int>>();
  } catch (const py::cast_error&) {
    RaiseInvalid("bits: not None, \"auto\", an int or a sequence of ints");
  }
  return {};
}

py::object Export(const std::string& store, const std::string& out, const std::string& format,
                  std::optional<double> cut_off, std::optional<double> target_error,
                  const py::object& bits, int jump_nodes) {
  if (format != "wavelet-tree") RaiseInvalid("format: '" + format + "' is not wavelet-tree");
  if (cut_off && target_error) RaiseInvalid("cut_off: give cut_off or target_error, not both");
  if (cut_off && !(*cut_off >= 0)) RaiseInvalid("cut_off: must be a number ≥ 0");
  if (target_error && !(*target_error >= 0)) RaiseInvalid("target_error: must be a number ≥ 0");
  WaveletTreeOptions options;
  options.bits = CodeBits(bits);
  options.jump_nodes = jump_nodes;
  if (cut_off) options.cut_off = *cut_off;
  if (target_error) options.target_error = *target_error;
  absl::StatusOr<nlohmann::json> header;
  {
    py::gil_scoped_release release;
    header = driver::ExportWaveletTrees(store, out, options);
  }
  return JsonToPython(Unwrap(std::move(header)));
}

}  // namespace

void AddExportBindings(py::module_& m) {
  m.def("export", &Export, py::arg("store"), py::arg("out"), py::arg("format"), py::arg("cut_off"),
        py::arg("target_error"), py::arg("bits"), py::arg("jump_nodes"),
        "a diffuse store's rows as wavelet-tree textures in `out`; the header as a dict "
        "(wavebake.export)");
}

}  // namespace wavebake::python
