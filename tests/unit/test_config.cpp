#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "temp_dir.hpp"
#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/config_text.hpp"

using ubersim::ConfigError;
using ubersim::ConfigFile;

namespace {

// Expects `action` to throw a ConfigError whose message contains every piece.
template <class F>
void expect_config_error(F action, const std::vector<std::string>& pieces) {
  try {
    action();
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& error) {
    for (const auto& piece : pieces) {
      EXPECT_NE(std::string(error.what()).find(piece), std::string::npos)
          << "'" << error.what() << "' lacks '" << piece << "'";
    }
  }
}

using ubersim::test::TempDir;

}  // namespace

TEST(Config, ReadsTypedValuesOfAnyLength) {
  const auto config = ConfigFile::parse(
      "# a robot\n"
      "MASS = 2.5            # kg\n"
      "\n"
      "WHEEL_ANGLES = 30 150 225 315   # deg\n"
      "NUM_WHEELS = 4\n"
      "NAME = \"omni four\"\n"
      "TAGS = fast small\n"
      "HAS_KICKER = yes\n"
      "COUNTS = -1 2 3\n",
      "robot.cfg");
  EXPECT_DOUBLE_EQ(config.real("MASS"), 2.5);
  EXPECT_EQ(config.reals("WHEEL_ANGLES", 4), (std::vector<double>{30, 150, 225, 315}));
  EXPECT_EQ(config.integer("NUM_WHEELS"), 4);
  EXPECT_EQ(config.string("NAME"), "omni four");
  EXPECT_EQ(config.strings("TAGS"), (std::vector<std::string>{"fast", "small"}));
  EXPECT_TRUE(config.boolean("HAS_KICKER"));
  EXPECT_EQ(config.integers("COUNTS"), (std::vector<std::int64_t>{-1, 2, 3}));
  EXPECT_NO_THROW(config.require_all_used());
}

TEST(Config, FallbacksApplyOnlyToMissingKeys) {
  const auto config = ConfigFile::parse("A = 1.5\n", "x.cfg");
  EXPECT_DOUBLE_EQ(config.real("A", 9.0), 1.5);
  EXPECT_DOUBLE_EQ(config.real("B", 9.0), 9.0);
  EXPECT_EQ(config.string("C", "d"), "d");
  EXPECT_FALSE(config.boolean("D", false));
}

TEST(Config, WrongTypeNamesFileLineAndExpectation) {
  const auto config = ConfigFile::parse("# header\nMASS = heavy # kg\n", "robots/r.cfg");
  expect_config_error([&] { config.real("MASS"); },
                      {"robots/r.cfg:2", "MASS", "expected a real number", "heavy"});
}

TEST(Config, WrongLengthNamesExpectedCount) {
  const auto config = ConfigFile::parse("POS = 1 2\n", "f.cfg");
  expect_config_error([&] { config.reals("POS", 3); },
                      {"f.cfg:1", "POS", "expected 3 values", "got 2"});
  expect_config_error([&] { config.real("POS"); }, {"f.cfg:1", "expected 1 value"});
}

TEST(Config, IntegerRejectsFraction) {
  const auto config = ConfigFile::parse("N = 2.5\n", "f.cfg");
  expect_config_error([&] { config.integer("N"); }, {"f.cfg:1", "expected an integer", "2.5"});
}

TEST(Config, RangeCheckNamesTheRange) {
  const auto config = ConfigFile::parse("P = 1.5\n", "f.cfg");
  expect_config_error([&] { config.real_in("P", 0.0, 1.0); }, {"f.cfg:1", "P", "[0, 1]", "1.5"});
}

TEST(Config, IntegerRangeCheckNamesTheRange) {
  const auto config = ConfigFile::parse("N = 65\nM = 64\n", "f.cfg");
  expect_config_error([&] { config.integer_in("N", 1, 64); }, {"f.cfg:1", "N", "[1, 64]", "65"});
  EXPECT_EQ(config.integer_in("M", 1, 64), 64);
}

TEST(Config, MissingKeyIsNamed) {
  const auto config = ConfigFile::parse("A = 1\n", "f.cfg");
  expect_config_error([&] { config.real("MASS"); }, {"f.cfg", "missing required key 'MASS'"});
}

TEST(Config, UnknownKeyIsAnErrorAtItsLine) {
  const auto config = ConfigFile::parse("MASS = 1\n\nMAS = 2\n", "f.cfg");
  config.real("MASS");
  expect_config_error([&] { config.require_all_used(); }, {"f.cfg:3", "unknown key 'MAS'"});
}

// A misspelt required key: the reader looks for GRAVITY before any
// unknown-key check, so the error must point at GRAVTY's line itself.
TEST(Config, MisspeltRequiredKeyIsNamedAtItsLineWithTheRightName) {
  TempDir dir;
  const auto path = dir.write("physics.cfg",
                              "# physics\n"
                              "STEP_RATE = 1000\n"
                              "GRAVTY = 9.81   # m/s^2\n"
                              "ERP = 0.2\n");
  const auto config = ConfigFile::load(path);
  config.real("STEP_RATE");
  expect_config_error([&] { config.real_in("GRAVITY", 0.1, 100.0); },
                      {"physics.cfg:3", "unknown key 'GRAVTY'", "did you mean 'GRAVITY'?"});
}

TEST(Config, MisspellingsAreFoundWithoutCaseAndWithSwappedLetters) {
  const auto config = ConfigFile::parse("gravity = 9.81\nSTPE_RATE = 1000\n", "p.cfg");
  expect_config_error([&] { config.real("GRAVITY"); },
                      {"p.cfg:1", "unknown key 'gravity'", "did you mean 'GRAVITY'?"});
  expect_config_error([&] { config.real("STEP_RATE"); },
                      {"p.cfg:2", "unknown key 'STPE_RATE'", "did you mean 'STEP_RATE'?"});
}

TEST(Config, MissingKeyWithNothingLikeItIsNamedAlone) {
  const auto config = ConfigFile::parse("STEP_RATE = 1000\n", "p.cfg");
  try {
    config.real("GRAVITY");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& error) {
    EXPECT_EQ(std::string(error.what()), "p.cfg: missing required key 'GRAVITY' (a real number)");
  }
}

// An optional key misspelt: the reader takes the fallback, and the unknown
// key names the key it was meant to be.
TEST(Config, UnknownKeyNamesTheOptionalKeyItMisspells) {
  const auto config = ConfigFile::parse("MASS = 1\nRADUIS = 0.1\n", "r.cfg");
  config.real("MASS");
  EXPECT_DOUBLE_EQ(config.real("RADIUS", 0.09), 0.09);
  expect_config_error([&] { config.require_all_used(); },
                      {"r.cfg:2", "unknown key 'RADUIS'", "did you mean 'RADIUS'?"});
}

// A key that is defined is not what an unknown key meant (CAMERA_1_X when
// only camera 0 exists), nor is a key far from it in spelling.
TEST(Config, UnknownKeySuggestsOnlyMissingKeysSpeltNearlyLikeIt) {
  const auto config = ConfigFile::parse("CAMERA_0_X = 1\nCAMERA_1_X = 2\nWEIGHT = 3\n", "v.cfg");
  config.real("CAMERA_0_X");
  config.real("MASS", 1.0);
  try {
    config.require_all_used();
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& error) {
    EXPECT_EQ(std::string(error.what()), "v.cfg:2: unknown key 'CAMERA_1_X'");
  }
}

TEST(Config, DuplicateKeyIsAnError) {
  expect_config_error([] { ConfigFile::parse("A = 1\nB = 2\nA = 3\n", "f.cfg"); },
                      {"f.cfg:3", "duplicate key 'A'", "line 1"});
}

TEST(Config, SyntaxErrors) {
  expect_config_error([] { ConfigFile::parse("JUST WORDS\n", "f.cfg"); }, {"f.cfg:1", "'='"});
  expect_config_error([] { ConfigFile::parse("A =   # nothing\n", "f.cfg"); },
                      {"f.cfg:1", "no value"});
  expect_config_error([] { ConfigFile::parse("BAD KEY = 1\n", "f.cfg"); }, {"f.cfg:1", "key"});
  expect_config_error([] { ConfigFile::parse("S = \"open\n", "f.cfg"); },
                      {"f.cfg:1", "unterminated"});
  expect_config_error([] { ConfigFile::parse("# x = 1\n= 3\n", "f.cfg"); }, {"f.cfg:2"});
}

TEST(Config, NonFiniteRealsAreRejected) {
  const auto config = ConfigFile::parse("A = nan\nB = inf\nC = 1e999\n", "f.cfg");
  expect_config_error([&] { config.real("A"); }, {"f.cfg:1", "expected a real number"});
  expect_config_error([&] { config.real("B"); }, {"f.cfg:2"});
  expect_config_error([&] { config.real("C"); }, {"f.cfg:3"});
}

TEST(Config, BaseFileIsExtendedAndOverridden) {
  TempDir dir;
  dir.write("base.cfg", "MASS = 2.0\nRADIUS = 0.09\n");
  const auto path = dir.write("variant.cfg", "BASE = base.cfg\nMASS = 2.5 # heavier\n");
  const auto config = ConfigFile::load(path);
  EXPECT_DOUBLE_EQ(config.real("MASS"), 2.5);
  EXPECT_DOUBLE_EQ(config.real("RADIUS"), 0.09);
  EXPECT_EQ(config.where("MASS"), path + ":2");
  EXPECT_EQ(config.where("RADIUS"), (dir.root() / "base.cfg").string() + ":2");
}

TEST(Config, UnknownKeyInBaseNamesTheBaseFile) {
  TempDir dir;
  dir.write("base.cfg", "MASS = 2.0\nTYPO = 1\n");
  const auto config = ConfigFile::load(dir.write("v.cfg", "BASE = base.cfg\n"));
  config.real("MASS");
  expect_config_error([&] { config.require_all_used(); }, {"base.cfg:2", "unknown key 'TYPO'"});
}

TEST(Config, BaseErrors) {
  TempDir dir;
  expect_config_error([&] { ConfigFile::load(dir.write("a.cfg", "BASE = missing.cfg\n")); },
                      {"a.cfg:1", "missing.cfg", "cannot open"});
  expect_config_error([&] { ConfigFile::load(dir.write("b.cfg", "A = 1\nBASE = a.cfg\n")); },
                      {"b.cfg:2", "BASE must come before"});
  dir.write("loop1.cfg", "BASE = loop2.cfg\n");
  expect_config_error([&] { ConfigFile::load(dir.write("loop2.cfg", "BASE = loop1.cfg\n")); },
                      {"loops"});
  expect_config_error([&] { ConfigFile::load(dir.write("c.cfg", "X = 1\nBAD\n")); }, {"c.cfg:2"});
}

TEST(Config, MissingFileIsNamed) {
  expect_config_error([] { ConfigFile::load("/nonexistent/robot.cfg"); },
                      {"/nonexistent/robot.cfg", "cannot open"});
}

TEST(Config, ConfigTextIsTheFileWholeOrANamedError) {
  TempDir dir;
  const std::string text = "# a field change\nFIELD_LENGTH = 9.0  # m\n";
  EXPECT_EQ(ubersim::read_config_text(dir.write("f.cfg", text)), text);
  expect_config_error([&] { ubersim::read_config_text(dir.root()); },
                      {dir.root().string(), "not a regular file"});
  expect_config_error([&] { ubersim::read_config_text(dir.path("missing.cfg")); },
                      {"missing.cfg", "cannot open"});
}

TEST(ConfigPaths, ResolvesNamesByKindAndListsAlternatives) {
  TempDir dir;
  dir.write("fields/division_b.cfg", "A = 1\n");
  dir.write("fields/division_a.cfg", "A = 1\n");
  EXPECT_EQ(ubersim::resolve_config(dir.root(), "fields", "division_b"),
            dir.root() / "fields/division_b.cfg");
  const auto explicit_path = dir.write("elsewhere/my.cfg", "A = 1\n");
  EXPECT_EQ(ubersim::resolve_config(dir.root(), "fields", explicit_path), explicit_path);
  expect_config_error([&] { ubersim::resolve_config(dir.root(), "fields", "division_c"); },
                      {"division_c", "no such fields config", "division_a, division_b"});
}
