// GET /api/openapi.json: the OpenAPI 3.1 document of the REST API, written by
// hand in server/openapi.json; its Scenario schema is docs/scenario.schema.json
// (one source for the file format and the API). Both are compiled in.
#include "routes/routes.hpp"

namespace rrlab::server {

namespace {
// "#/$defs/X" (the schema file's own definitions) -> "#/components/schemas/X"
void move_refs(nlohmann::json& node) {
  if (node.is_object()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      if (it.key() == "$ref" && it->is_string() && it->get<std::string>().rfind("#/$defs/", 0) == 0)
        *it = "#/components/schemas/" + it->get<std::string>().substr(8);
      else
        move_refs(*it);
    }
  } else if (node.is_array()) {
    for (auto& item : node) move_refs(item);
  }
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
    return doc;
  }();
  return document;
}

ApiResponse get_openapi(RouteContext&) { return json_response(200, openapi_document()); }

}  // namespace rrlab::server
