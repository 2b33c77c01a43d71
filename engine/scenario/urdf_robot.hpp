// The "urdf" robot kind of a scenario: where its URDF comes from (a file
// confined to the scenario's directory, or inline text) and how it becomes a
// Model. Errors are ScenarioErrors naming the robot's JSON path.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include <rrlab/model/model.hpp>
#include <rrlab/scenario/json_reader.hpp>

namespace rrlab {

// Reads robot.file (resolved in `dir`, or the catalogue directory when empty)
// or robot.urdf, base_link, tip_link, link_radius, base and base_rpy.
// `urdf_text` receives the URDF read, so the caller can carry it inline;
// empty when the URDF uses mesh files (the scenario must keep its "file").
Model parse_urdf_robot(JsonObject& robot, double radians_per_unit, const std::string& dir, std::string& urdf_text);

// The text of a URDF file named relative to `dir`, refused when the path is
// absolute or leads outside `dir` (after resolving "..", symbolic links).
std::string read_confined_file(const std::string& file, const std::string& dir, const std::string& path);
// The resolved path of `file` (relative to `dir`, or to `dir`/`subdir`),
// refused like read_confined_file when it leaves `dir`.
std::string confined_path(const std::string& file, const std::string& dir, const std::string& path,
                          const std::string& subdir = {});
// Why a mesh path cannot be used as given: a package:// or file:// URI, which
// rrlab does not resolve ("...; give a path relative to the `relative_to`");
// empty when it is a plain path.
std::string uri_problem(const std::string& file, const std::string& relative_to);

}  // namespace rrlab
