// SPDX-License-Identifier: MIT
// The field dictionary is the one description of every field: names are unique, every model's
// fields come from it, and docs/fields.md lists each with its location, type and unit.
#include <gtest/gtest.h>

#include <set>

#include "runnel/models/fields.hpp"
#include "runnel/models/registry.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

TEST(FieldDictionary, NamesAreUniqueAndWellFormed) {
  std::set<std::string> seen;
  for (const FieldDescription& f : field_dictionary()) {
    EXPECT_TRUE(seen.insert(f.name).second) << f.name << " is described twice";
    EXPECT_NE(f.name.find("__"), std::string::npos) << f.name << ": what__quantity";
    EXPECT_FALSE(f.unit.empty()) << f.name;
    EXPECT_FALSE(f.doc.empty()) << f.name;
    EXPECT_GE(f.components, f.name.rfind("ground__", 0) == 0 ? 0 : 1) << f.name;
  }
  EXPECT_THROW(field_description("no__such_field"), std::out_of_range);
}

TEST(FieldDictionary, DocsListEveryFieldWithItsDescription) {
  const std::string docs = test::read_text(test::source_dir() + "/docs/fields.md");
  for (const FieldDescription& f : field_dictionary()) {
    const std::string row =
        "| `" + f.name + "` | " + to_string(f.location) + " | " + to_string(f.type) + " | " +
        (f.components > 0 ? std::to_string(f.components) : "per stratum") + " | " + f.unit + " |";
    EXPECT_NE(docs.find(row), std::string::npos) << "docs/fields.md lacks or differs: " << row;
  }
}

TEST(FieldDictionary, EveryModelIsDocumented) {
  const std::string docs = test::read_text(test::source_dir() + "/docs/fields.md");
  for (const ModelEntry& e : model_registry()) {
    const std::string row = "| `" + e.info().name + "` | `" + e.info().class_name + "` |";
    EXPECT_NE(docs.find(row), std::string::npos) << row;
  }
}

}  // namespace
}  // namespace runnel
