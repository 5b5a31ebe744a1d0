//===- SectionsTest.cpp - %%% section splitting ---------------------------===//

#include "simit/Frontend/Frontend.h"

#include <gtest/gtest.h>

using namespace simit::frontend;

namespace {

TEST(Sections, UnsectionedFileIsOneProgram) {
  auto sections = splitSections("func f()\nend\n%%% not a split\n");
  ASSERT_EQ(sections.size(), 1u);
  EXPECT_FALSE(sections[0].disabled);
  EXPECT_EQ(sections[0].text.size(), 29u);
}

TEST(Sections, SplitsAtLineStarts) {
  auto sections = splitSections("%%% one\na\n%%%- two\nb\n  %%% no\n%%%\nc");
  ASSERT_EQ(sections.size(), 3u);
  EXPECT_EQ(sections[0].name, "one");
  EXPECT_EQ(sections[0].text, "%%% one\na\n");
  EXPECT_TRUE(sections[1].disabled);
  EXPECT_EQ(sections[1].name, "two");
  EXPECT_EQ(sections[1].text, "%%%- two\nb\n  %%% no\n");
  EXPECT_EQ(sections[2].name, "");
  EXPECT_EQ(sections[2].firstLine, 6u);
  EXPECT_EQ(sections[2].index, 2u);
}

TEST(Sections, CommentedOutCodeStartsEmptySections) {
  auto sections = splitSections("%%% a\n%%% %! f() == 1;\n%%% func g()\n");
  ASSERT_EQ(sections.size(), 3u);
  EXPECT_EQ(sections[1].name, "%! f() == 1;");
  EXPECT_EQ(sections[2].name, "func g()");
}

TEST(Sections, BareDisabledHeader) {
  auto sections = splitSections("%%%-\nx\n");
  ASSERT_EQ(sections.size(), 1u);
  EXPECT_TRUE(sections[0].disabled);
  EXPECT_EQ(sections[0].name, "");
}

} // namespace
