// The JSON reader: RFC 8259 values, dampbound's non-finite numbers, one-line errors.
#include "core/io/json_read.hpp"

#include <gtest/gtest.h>

#include <clocale>
#include <cmath>

#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

TEST(JsonRead, ReadsEveryKindOfValue) {
  const JsonValue v = parse_json(
      R"({"a": [1, -2.5e-3, 0.1], "s": "x\"y\\n\u00e9", "t": true, "f": false, "n": null,
          "o": {}, "e": []})",
      "t.json");
  ASSERT_EQ(v.kind, JsonValue::Kind::object);
  const JsonValue* a = v.find("a");
  ASSERT_TRUE(a && a->array.size() == 3);
  EXPECT_EQ(a->array[1].number, -2.5e-3);
  EXPECT_EQ(a->array[2].number, 0.1);
  EXPECT_EQ(v.find("s")->string, "x\"y\\n\xc3\xa9");
  EXPECT_TRUE(v.find("t")->boolean);
  EXPECT_EQ(v.find("n")->kind, JsonValue::Kind::null);
  EXPECT_EQ(v.find("o")->kind, JsonValue::Kind::object);
  EXPECT_EQ(v.find("missing"), nullptr);
}

TEST(JsonRead, NonFiniteNumbersRoundTrip) {
  for (double x : {1.0 / 3, -1e300, 0.0, std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity()}) {
    const JsonValue v = parse_json(json_limit_text(x), "t.json");
    EXPECT_EQ(json_limit(v, "t.json", "x"), x);
  }
  EXPECT_TRUE(std::isnan(json_limit(parse_json(json_limit_text(NAN), "t"), "t", "x")));
  EXPECT_THROW(json_limit(parse_json("\"big\"", "t"), "t", "x"), InputError);
}

TEST(JsonRead, NumbersKeepTheirPointUnderACommaLocale) {
  const char* old = std::setlocale(LC_NUMERIC, nullptr);
  const std::string saved = old ? old : "C";
  if (!std::setlocale(LC_NUMERIC, "de_DE.UTF-8")) GTEST_SKIP() << "no de_DE locale";
  const double x = parse_json("[0.57]", "t").array[0].number;
  std::setlocale(LC_NUMERIC, saved.c_str());
  EXPECT_EQ(x, 0.57);
}

TEST(JsonRead, BadTextIsOneLineNamingTheFileAndLine) {
  for (const char* bad : {"", "{", "[1,]", "{\"a\" 1}", "01x", "\"abc", "[1] 2", "tru", "-"}) {
    try {
      parse_json(bad, "base.json");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("base.json: line 1: JSON: ", 0), 0u) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos);
    }
  }
  EXPECT_THROW(parse_json(std::string(100, '[') + std::string(100, ']'), "d"), InputError);
}

}  // namespace
}  // namespace dampbound
