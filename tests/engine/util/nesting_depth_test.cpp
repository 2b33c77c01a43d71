// The depth checks run before any recursive parser: they must find the level
// too many at the right byte, ignore brackets and tags inside strings,
// comments and attribute values, and take deep input without recursion.
#include <rrlab/util/nesting_depth.hpp>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>

namespace rrlab {
namespace {

std::string nested_json(int levels) {
  std::string text;
  for (int i = 0; i < levels; ++i) text += "{\"a\":";
  text += "1";
  text.append(levels, '}');
  return text;
}

std::string nested_xml(int levels) {
  std::string text;
  for (int i = 0; i < levels; ++i) text += "<a>";
  for (int i = 0; i < levels; ++i) text += "</a>";
  return text;
}

TEST(JsonDepth, AtTheLimitPassesOneMoreLevelIsFoundAtItsBracket) {
  EXPECT_FALSE(json_too_deep_at(nested_json(kMaxJsonDepth)));
  const std::string deep = nested_json(kMaxJsonDepth + 1);
  const auto at = json_too_deep_at(deep);
  ASSERT_TRUE(at);
  EXPECT_EQ(*at, std::size_t(kMaxJsonDepth) * 5);  // "{\"a\":" is 5 bytes
  EXPECT_EQ(deep[*at], '{');
  EXPECT_FALSE(json_too_deep_at("[[[]]]", 3));
  EXPECT_EQ(json_too_deep_at("[[{}]]", 2), 2u);
}

TEST(JsonDepth, BracketsInStringsDoNotCount) {
  EXPECT_FALSE(json_too_deep_at(R"({"a": "[[[[[[", "b": "\"[[[[[[\\"})", 1));
  // an escaped backslash ends before the quote: the string closes there
  EXPECT_EQ(json_too_deep_at(R"({"a": "\\", "b": [[]]})", 2), 18u);
  // closing more than was opened does not make room for deeper levels
  EXPECT_EQ(json_too_deep_at("]]]][[[", 2), 6u);
}

TEST(JsonDepth, ParseJsonRefusesDeepDocumentsAndParsesTheRest) {
  const nlohmann::json doc = parse_json(nested_json(kMaxJsonDepth));
  EXPECT_TRUE(doc.is_object());
  try {
    parse_json(nested_json(60000));  // the crash report's document: 360 KB
    FAIL() << "no error";
  } catch (const TooDeepError& e) {
    EXPECT_EQ(e.byte(), std::size_t(kMaxJsonDepth) * 5 + 1);
    EXPECT_EQ(std::string(e.what()), "JSON nested deeper than 64 levels at byte 321");
  }
  EXPECT_THROW(parse_json("{\"a\": }"), nlohmann::json::parse_error);
}

TEST(XmlDepth, CountsElementsNotEmptyElementsCommentsOrAttributes) {
  EXPECT_FALSE(xml_too_deep_at(nested_xml(kMaxXmlDepth)));
  const std::string deep = nested_xml(kMaxXmlDepth + 1);
  EXPECT_EQ(xml_too_deep_at(deep), std::size_t(kMaxXmlDepth) * 3);
  EXPECT_FALSE(xml_too_deep_at(R"(<?xml version="1.0"?><!-- <a><a><a> --><r x="<a><a>" y='>'><b/><b/></r>)", 1));
  EXPECT_FALSE(xml_too_deep_at("<r><![CDATA[<a><a><a>]]><!DOCTYPE x><b></b></r>", 2));
  EXPECT_EQ(xml_too_deep_at("<r><b><c/></b></r>", 1), 3u);
  // siblings close what they opened
  EXPECT_FALSE(xml_too_deep_at("<r><b></b><b></b><b></b></r>", 2));
}

TEST(XmlDepth, TheCrashReportsDocumentIsFoundWithoutRecursion) {
  const std::string deep = nested_xml(140000);  // 980 KB: exit 139 in TinyXML before the check
  EXPECT_EQ(xml_too_deep_at(deep), std::size_t(kMaxXmlDepth) * 3);
  EXPECT_FALSE(xml_too_deep_at(std::string(1000000, '<')));  // unterminated tags: never closes one
}

}  // namespace
}  // namespace rrlab
