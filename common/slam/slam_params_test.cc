#include "common/slam/slam_params.h"

#include <gmock/gmock.h>
#include <google/protobuf/descriptor.h>
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "common/io/file_bytes.h"
#include "common/util/error.h"
#include "common/util/error_testing.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

namespace pb = google::protobuf;
using testing::ErrorOf;
using ::testing::HasSubstr;

// Calls `visit` with the dotted name and descriptor of every scalar field below `d`.
void ForEachParameter(
    const pb::Descriptor& d, const std::string& prefix,
    const std::function<void(const std::string&, const pb::FieldDescriptor&)>& visit) {
  for (int i = 0; i < d.field_count(); ++i) {
    const pb::FieldDescriptor& f = *d.field(i);
    const std::string name = prefix + f.name();
    if (f.cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      ForEachParameter(*f.message_type(), name + ".", visit);
    } else {
      visit(name, f);
    }
  }
}

// A value of the field's type that is not its default, as text.
std::string OtherValue(const pb::FieldDescriptor& f) {
  switch (f.cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_DOUBLE:
      return std::to_string(f.default_value_double() + 0.125);
    case pb::FieldDescriptor::CPPTYPE_UINT32:
      return std::to_string(f.default_value_uint32() + 3);
    case pb::FieldDescriptor::CPPTYPE_UINT64:
      return std::to_string(f.default_value_uint64() + 3);
    case pb::FieldDescriptor::CPPTYPE_BOOL:
      return f.default_value_bool() ? "false" : "true";
    default:
      return f.default_value_string() + "x";
  }
}

TEST(SlamParamsTest, EveryParameterDeclaresItsDefault) {
  ForEachParameter(*proto::SlamParams::descriptor(), "",
                   [](const std::string& name, const pb::FieldDescriptor& f) {
                     EXPECT_FALSE(f.is_repeated()) << name;
                     if (name != "log") {
                       EXPECT_TRUE(f.has_default_value()) << name;
                     }
                   });
}

TEST(SlamParamsTest, UnsetFieldsReadAsTheirDefaultsAndCompletingSetsThemAll) {
  const proto::SlamParams complete = WithDefaults({});
  EXPECT_EQ(complete.method(), "rss");
  EXPECT_EQ(complete.seed(), 1u);
  EXPECT_EQ(complete.rss().local().fitness(), "eval1");
  EXPECT_EQ(complete.rss().global().generations(), 100u);
  EXPECT_FALSE(complete.has_log());
  // Completing sets every field of the top level and of the run's method, whichever it is.
  for (const std::string& method : SlamMethodNames()) {
    proto::SlamParams chosen;
    chosen.set_method(method);
    const std::string text = SlamParamsText(WithDefaults(chosen));
    ForEachParameter(*proto::SlamParams::descriptor(), "",
                     [&](const std::string& name, const pb::FieldDescriptor& f) {
                       const bool top = name.find('.') == std::string::npos;
                       if (name == "log" || !(top || name.starts_with(method + "."))) return;
                       // The field as the message holding it sees it.
                       EXPECT_NE(text.find(f.name() + ":"), std::string::npos) << name;
                     });
  }
}

// Every parameter set by its dotted name reaches the message, survives completion, and comes
// back from the text --print-params writes and --config reads. A field the text or the
// completion dropped would fail here, whichever it is.
TEST(SlamParamsTest, EveryParameterRoundTripsThroughItsNameAndTheTextFile) {
  proto::SlamParams set;
  std::vector<std::pair<std::string, const pb::FieldDescriptor*>> fields;
  ForEachParameter(*proto::SlamParams::descriptor(), "",
                   [&](const std::string& name, const pb::FieldDescriptor& f) {
                     if (name == "log" || name == "method") return;
                     SetSlamParam(set, name, OtherValue(f));
                     fields.emplace_back(name, &f);
                   });
  ASSERT_GT(fields.size(), 60u);
  const TempDir dir;
  WriteFileBytes(dir / "p.txt", SlamParamsText(set));
  const proto::SlamParams back = ReadSlamParamsFile((dir / "p.txt").string());
  for (const auto& [name, field] : fields) {
    EXPECT_EQ(SlamParamText(back, name), SlamParamText(set, name)) << name;
    EXPECT_NE(SlamParamText(back, name), SlamParamText(WithDefaults({}), name)) << name;
  }
  EXPECT_EQ(back.SerializeAsString(), set.SerializeAsString());
}

TEST(SlamParamsTest, TheMethodsAreTheMessagesOfTheParameters) {
  EXPECT_EQ(SlamMethodNames(), (std::vector<std::string>{"rss", "immune"}));
  proto::SlamParams p;
  p.set_method("gslam");
  EXPECT_THAT(ErrorOf([&] { CheckOneMethodsParams(p); }), HasSubstr("(rss, immune)"));
  EXPECT_THAT(ErrorOf([&] { SetSlamParam(p, "local.particles", "3"); }), HasSubstr("gslam"));
}

TEST(SlamParamsTest, ChoosingTheMethodByNameGivesNoOtherMethodsParameters) {
  proto::SlamParams p;
  SetSlamParam(p, "method", "immune");
  EXPECT_FALSE(p.has_rss());
  EXPECT_NO_THROW(CheckOneMethodsParams(p));
  SetSlamParam(p, "search.population", "20");
  EXPECT_EQ(p.immune().search().population(), 20u);
  EXPECT_THAT(ErrorOf([&] { SetSlamParam(p, "local.particles", "3"); }),
              HasSubstr("local.particles"));
}

TEST(SlamParamsTest, NamesMayLeaveOutTheMethodsPrefix) {
  proto::SlamParams p;
  SetSlamParam(p, "local.particles", "20");
  SetSlamParam(p, "rss.global.islands", "3");
  SetSlamParam(p, "seed", "7");
  SetSlamParam(p, "global.enabled", "false");
  EXPECT_EQ(p.rss().local().particles(), 20u);
  EXPECT_EQ(p.rss().global().islands(), 3u);
  EXPECT_EQ(p.seed(), 7u);
  EXPECT_FALSE(p.rss().global().enabled());
  EXPECT_THAT(ErrorOf([&] { SetSlamParam(p, "local.nope", "1"); }), HasSubstr("local.nope"));
  EXPECT_THAT(ErrorOf([&] { SetSlamParam(p, "local", "1"); }), HasSubstr("local"));
  EXPECT_THAT(ErrorOf([&] { SetSlamParam(p, "local.particles", "x"); }),
              HasSubstr("local.particles"));
  EXPECT_THAT(ErrorOf([&] { SetSlamParam(p, "local.particles", "-1"); }), HasSubstr("'-1'"));
  EXPECT_THAT(ErrorOf([&] { SetSlamParam(p, "local.inertia", "nan"); }), HasSubstr("'nan'"));
  EXPECT_THAT(ErrorOf([&] { SetSlamParam(p, "global.enabled", "yes"); }), HasSubstr("'yes'"));
  EXPECT_THAT(ErrorOf([&] { SetSlamParam(p, "log", "x.clf"); }), HasSubstr("--log"));
}

TEST(SlamParamsTest, AFileThatIsNoParameterFileIsRefusedWithItsLine) {
  const TempDir dir;
  WriteFileBytes(dir / "bad.txt", "seed: 3\nrss { local { particles: many } }\n");
  EXPECT_THAT(ErrorOf([&] { ReadSlamParamsFile((dir / "bad.txt").string()); }),
              HasSubstr("bad.txt: line 2"));
  WriteFileBytes(dir / "log.txt", "log: \"x.clf\"\n");
  EXPECT_THAT(ErrorOf([&] { ReadSlamParamsFile((dir / "log.txt").string()); }), HasSubstr("--log"));
  EXPECT_THAT(ErrorOf([&] { ReadSlamParamsFile((dir / "none.txt").string()); }),
              HasSubstr("none.txt"));
}

}  // namespace
}  // namespace evoslam
