// GET /api/openapi.json: the OpenAPI 3.1 document of the REST API, written by
// hand in server/openapi.json; its Scenario schema is docs/scenario.schema.json
// (one source for the file format and the API). Both are compiled in.
#include <rrlab/server/routes/routes.hpp>

#include <functional>

#include <rrlab/generators/generators.hpp>
#include <rrlab/sim/frame_fields.hpp>

namespace rrlab::server {

namespace {
// Calls `rewrite(key, value)` on every member of every object below `node`;
// a member it rewrote (it returns true) is not descended into.
void rewrite_members(nlohmann::json& node, const std::function<bool(const std::string&, nlohmann::json&)>& rewrite) {
  if (node.is_object()) {
    for (auto it = node.begin(); it != node.end(); ++it)
      if (!rewrite(it.key(), *it)) rewrite_members(*it, rewrite);
  } else if (node.is_array()) {
    for (auto& item : node) rewrite_members(item, rewrite);
  }
}

// "#/$defs/X" (the schema file's own definitions) -> "#/components/schemas/X"
void move_refs(nlohmann::json& node) {
  rewrite_members(node, [](const std::string& key, nlohmann::json& value) {
    if (key != "$ref" || !value.is_string() || value.get<std::string>().rfind("#/$defs/", 0) != 0) return false;
    value = "#/components/schemas/" + value.get<std::string>().substr(8);
    return true;
  });
}

// A frame field's JSON schema, from its kind (sim/frame_fields.hpp).
nlohmann::json frame_field_schema(const FrameField& field) {
  const nlohmann::json number = {{"type", {"number", "null"}}};
  const auto array = [&](int size) {
    nlohmann::json a = {{"type", "array"}, {"items", number}};
    if (size > 0) a["minItems"] = size, a["maxItems"] = size;
    return a;
  };
  nlohmann::json schema;
  switch (field.kind) {
    case FrameFieldKind::count: schema = {{"type", "integer"}}; break;
    case FrameFieldKind::link: schema = {{"type", "integer"}, {"minimum", 0}}; break;
    case FrameFieldKind::flag: schema = {{"type", "boolean"}}; break;
    case FrameFieldKind::number: schema = number; break;
    case FrameFieldKind::joints:
    case FrameFieldKind::diagnostics: schema = array(0); break;
    case FrameFieldKind::vec3: schema = array(3); break;
    case FrameFieldKind::quaternion: schema = array(4); break;
  }
  std::string description(field.description);
  if (!field.unit.empty()) description += " (" + std::string(field.unit) + ")";
  schema["description"] = description;
  return schema;
}

// The stored Frame's properties: the blob fields of the frame field table, the
// metrics nested as the JSON writer nests them (sim/frame_json.cpp).
void fill_frame_schema(nlohmann::json& frame) {
  nlohmann::json properties = {{"seq", {{"type", "integer"}}}}, required = {"seq"};
  nlohmann::json metrics = nlohmann::json::object(), metrics_required = nlohmann::json::array();
  for (const FrameField& field : kFrameFields) {
    if ((field.outputs & kFrameBlob) == 0 || (field.outputs & kFrameJson) == 0) continue;
    const std::string name(field.name);
    if (field.metric) {
      metrics[name] = frame_field_schema(field);
      metrics_required.push_back(name);
    } else {
      properties[name] = frame_field_schema(field);
      required.push_back(name);
    }
  }
  if (!metrics.empty()) {
    properties["metrics"] = {{"type", "object"}, {"properties", metrics}, {"required", metrics_required},
                             {"additionalProperties", false}};
    required.push_back("metrics");
  }
  frame["properties"] = properties;
  frame["required"] = required;
  frame["additionalProperties"] = false;
}

// Lists the document takes from rrlab's tables rather than spelling out: every
// "generator" property's enum is the generator registry's families.
void fill_from_tables(nlohmann::json& node) {
  rewrite_members(node, [](const std::string& key, nlohmann::json& value) {
    if (key != "generator" || !value.is_object() || !value.contains("enum")) return false;
    value["enum"] = generator_families();
    return true;
  });
}
}  // namespace

extern const char kOpenApiText[];
extern const char kScenarioSchemaText[];

const nlohmann::json& openapi_document() {
  static const nlohmann::json document = [] {
    nlohmann::json doc = nlohmann::json::parse(kOpenApiText);
    nlohmann::json scenario = nlohmann::json::parse(kScenarioSchemaText);
    // the schema's own $defs move to the document's components, where its $refs point
    nlohmann::json defs = scenario.value("$defs", nlohmann::json::object());
    scenario.erase("$defs");
    scenario.erase("$schema");
    scenario.erase("$id");
    move_refs(defs);
    move_refs(scenario);
    nlohmann::json& schemas = doc["components"]["schemas"];
    for (auto it = defs.begin(); it != defs.end(); ++it) {
      if (schemas.contains(it.key())) throw std::logic_error("openapi.json defines " + it.key() + " twice");
      schemas[it.key()] = it.value();
    }
    schemas["Scenario"] = scenario;
    fill_from_tables(doc);
    fill_frame_schema(schemas["Frame"]);  // the frame field table's stored fields
    return doc;
  }();
  return document;
}

ApiResponse get_openapi(RouteContext&) { return json_response(200, openapi_document()); }

}  // namespace rrlab::server
