// The settings schema (frugal/Settings.h): every setting reads back what it wrote in each form a
// front end uses (the command line's text, a settings file's JSON), refuses what is not of its
// kind or range with expected()'s words, and settingsProblem refuses every conflict the table
// declares, with the settings named in order. The command line, settings files and Python against
// each other: python/tests/test_schema.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include <frugal/Renderer.h>
#include <frugal/Settings.h>

namespace frugal {
namespace {

// A value of `info` other than the default's, within its range.
SettingValue otherValue(const SettingInfo& info, const SettingValue& now) {
    switch (info.kind) {
        case SettingKind::Switch:
            return !std::get<bool>(now);
        case SettingKind::Whole: {
            const long long v = std::get<long long>(now);
            return v < info.max ? v + 1 : v - 1;
        }
        case SettingKind::Pair: {
            const auto p = std::get<std::array<long long, 2>>(now);
            return std::array<long long, 2>{p[0] < info.max ? p[0] + 1 : p[0] - 1, p[1] > info.min ? p[1] - 1 : p[1] + 1};
        }
        case SettingKind::Choice:
            return std::string(info.choices.back().name == std::get<std::string>(now) ? info.choices.front().name
                                                                                     : info.choices.back().name);
        case SettingKind::Colour:
            return std::vector<double>{0.25, 0.5, 0.75, 0.125};
        case SettingKind::Real:
            return std::get<double>(now) < info.high ? std::min(info.high, std::get<double>(now) + 0.5) : info.low;
        case SettingKind::Text:
            return std::get<std::string>(now) + "other, with \"quotes\" and spaces.hdr";
    }
    return now;
}

TEST(SettingsSchemaTest, NamesAreUniqueAndFoundInBothSpellings) {
    std::set<std::string> names;
    for (const SettingInfo& info : settingInfos()) {
        EXPECT_TRUE(names.insert(info.name).second) << info.name;
        EXPECT_EQ(findSetting(info.name), &info);
        EXPECT_EQ(findSetting(info.pythonName()), &info);
        EXPECT_FALSE(info.help.empty()) << info.name;
        EXPECT_TRUE(info.get && info.put) << info.name;
        if (info.kind == SettingKind::Choice) {
            EXPECT_FALSE(info.choices.empty()) << info.name;
        }
    }
    EXPECT_EQ(findSetting("cull_bins")->name, "cull-bins");
    EXPECT_EQ(findSetting("nope"), nullptr);
}

TEST(SettingsSchemaTest, EveryValueReadsBackFromTextAndJson) {
    for (const SettingInfo& info : settingInfos()) {
        Settings s;
        const SettingValue value = otherValue(info, info.get(s));
        ASSERT_EQ(setSetting(s, info, value), "") << info.name;
        const SettingValue got = info.get(s);
        if (info.kind == SettingKind::Colour) {
            EXPECT_EQ(settingText(info, got), "0.25,0.5,0.75,0.125");
        } else {
            EXPECT_EQ(got, value) << info.name;
        }
        // The command line's text.
        const std::optional<SettingValue> parsed = parseSettingText(info, settingText(info, got));
        ASSERT_TRUE(parsed) << info.name << ": " << settingText(info, got);
        Settings fromText;
        ASSERT_EQ(setSetting(fromText, info, *parsed), "") << info.name;
        EXPECT_EQ(settingsJson(fromText), settingsJson(s)) << info.name;
        // A settings file.
        Result<SettingsFile> file = parseSettingsJson(settingsJson(s), "f");
        ASSERT_TRUE(file) << file.error().message;
        EXPECT_EQ(settingsJson(file->settings), settingsJson(s)) << info.name;
        EXPECT_NE(settingsJson(s), settingsJson(Settings{})) << info.name << " changed nothing";
    }
}

TEST(SettingsSchemaTest, ValuesOutOfTheirKindOrRangeAreRefusedWithTheExpectedWords) {
    const auto refusal = [](const char* name, const SettingValue& v) {
        Settings s;
        const Settings before = s;
        const std::string why = setSetting(s, *findSetting(name), v);
        EXPECT_EQ(settingsJson(s), settingsJson(before)) << "a refused value changes nothing";
        return why;
    };
    EXPECT_EQ(refusal("threads", 257LL), "is not a whole number from 0 to 256");
    EXPECT_EQ(refusal("threads", std::string("4")), "is not a whole number from 0 to 256");
    EXPECT_EQ(refusal("size", std::array<long long, 2>{0, 5}), "is not a size (WxH, each 1 to 65536)");
    EXPECT_EQ(refusal("cull-bins", std::array<long long, 2>{4, 1025}), "is not a bin grid (TxP, each 1 to 1024)");
    EXPECT_EQ(refusal("cull", std::string("Conservative")), "is not a method (" + namesOf(kCulls) + ")");
    EXPECT_EQ(refusal("reuse", 1LL), "is not true or false");
    EXPECT_EQ(refusal("background", std::vector<double>{1, 1}), "is not a colour (r,g,b or r,g,b,a, each 0 to 1)");
    EXPECT_EQ(refusal("background", std::vector<double>{1, 1, 1.5}), "is not a colour (r,g,b or r,g,b,a, each 0 to 1)");
    EXPECT_FALSE(parseSettingText(*findSetting("size"), "80x"));
    EXPECT_FALSE(parseSettingText(*findSetting("threads"), "2.5"));
    EXPECT_FALSE(parseSettingText(*findSetting("background"), "1,nan,1"));
}

// A Settings built in C++ may hold anything: the check of the whole finds a value out of range as
// the front ends refuse it, and Renderer::create refuses it before opening anything.
TEST(SettingsSchemaTest, AWholeSettingsIsCheckedValueByValue) {
    Settings s;
    s.threads = 999;
    std::optional<SettingsProblem> problem = settingsProblem(s);
    ASSERT_TRUE(problem);
    EXPECT_TRUE(problem->value);
    EXPECT_EQ(describe(*problem, s), "threads 999 is not a whole number from 0 to 256");
    s = Settings{};
    s.cull = Cull(200);
    problem = settingsProblem(s);
    ASSERT_TRUE(problem);
    EXPECT_EQ(problem->settings, std::vector<std::string>{"cull"});
    s = Settings{};
    s.width = 0;
    Result<Renderer> made = Renderer::create(Scene{}, s);
    ASSERT_FALSE(made);
    EXPECT_EQ(made.error().message, "size 0x600 is not a size (WxH, each 1 to 65536)");
    EXPECT_TRUE(made.error().aboutSetting);
}

// Every declared conflict is refused, naming its two settings in order; every method whose traits
// say it cannot go with reuse (or a hidden-surface mode) is refused with the traits' words.
TEST(SettingsSchemaTest, EveryConflictIsRefusedWithItsSettingsNamed) {
    std::set<std::pair<std::string, std::string>> seen;
    for (const Cull cull : kCulls) {
        Settings s;
        s.cull = cull;
        s.reuse = true;
        const std::optional<SettingsProblem> problem = settingsProblem(s);
        ASSERT_EQ(problem.has_value(), !traitsOf(cull).notWithReuse.empty()) << toString(cull);
        if (!problem) continue;
        EXPECT_EQ(problem->why, traitsOf(cull).notWithReuse);
        EXPECT_EQ(describe(*problem, s), "reuse with cull " + std::string(toString(cull)) + ": " + problem->why);
        seen.insert({problem->settings[0], problem->settings[1]});
    }
    for (const Hsr hsr : kHsrs)
        for (const Cull cull : kCulls) {
            Settings s;
            s.hsr = hsr;
            s.cull = cull;
            const std::optional<SettingsProblem> problem = settingsProblem(s);
            const bool refused = traitsOf(hsr).plans && !traitsOf(cull).notWithHsr.empty();
            ASSERT_EQ(problem.has_value(), refused) << toString(hsr) << " " << toString(cull);
            if (problem) seen.insert({problem->settings[0], problem->settings[1]});
        }
    Settings s;
    s.hsr = Hsr::Adaptive;
    s.reuse = true;
    ASSERT_TRUE(settingsProblem(s));
    EXPECT_EQ(describe(*settingsProblem(s), s),
              "hsr adaptive with reuse: reuse redraws what moved with the z-buffer over the static image");
    seen.insert({"hsr", "reuse"});
    s = Settings{};
    s.interp = DepthInterp::Span;
    ASSERT_TRUE(settingsProblem(s));
    seen.insert({settingsProblem(s)->settings[0], settingsProblem(s)->settings[1]});
    s.backend = BackendKind::Software;
    EXPECT_FALSE(settingsProblem(s)) << "span on the software backend";
    s.depthFormat = DepthFormat::D32F;
    ASSERT_TRUE(settingsProblem(s));
    seen.insert({settingsProblem(s)->settings[0], settingsProblem(s)->settings[1]});
    // More than one sample: not with the span engine, nor with the methods that test pixel centres.
    s = Settings{};
    s.samples = 4;
    s.backend = BackendKind::Software;
    EXPECT_FALSE(settingsProblem(s));
    s.interp = DepthInterp::Dda;
    ASSERT_TRUE(settingsProblem(s));
    EXPECT_EQ(describe(*settingsProblem(s), s), "samples 4 with interp dda: the span engine models one sample a pixel");
    seen.insert({settingsProblem(s)->settings[0], settingsProblem(s)->settings[1]});
    s.interp = DepthInterp::Exact;
    for (const Cull cull : kCulls) {
        s.cull = cull;
        const std::optional<SettingsProblem> problem = settingsProblem(s);
        ASSERT_EQ(problem.has_value(), traitsOf(cull).occlusion || traitsOf(cull).idPass) << toString(cull);
        if (problem) seen.insert({problem->settings[0], problem->settings[1]});
    }
    s.samples = 1;
    s.cull = Cull::Occlusion;
    EXPECT_FALSE(settingsProblem(s));
    // A map gives the environment's radiance: the uniform one's may stay at its default only.
    s = Settings{};
    s.environmentMap = "sky.hdr";
    EXPECT_FALSE(settingsProblem(s));
    s.environment = 1.0f;
    ASSERT_TRUE(settingsProblem(s));
    EXPECT_EQ(describe(*settingsProblem(s), s),
              "environment 1 with environment-map sky.hdr: a map gives the environment's radiance itself");
    seen.insert({settingsProblem(s)->settings[0], settingsProblem(s)->settings[1]});
    // The table's conflicts are exactly those met above, and each names settings of the schema.
    std::set<std::pair<std::string, std::string>> declared;
    for (const SettingsConflict& c : settingsConflicts()) {
        EXPECT_TRUE(findSetting(c.first) && findSetting(c.second)) << c.first << " " << c.second;
        declared.insert({c.first, c.second});
    }
    EXPECT_EQ(seen, declared);
}

// A front end's spelling names the settings its own way, and may leave one out; the words after
// the names are the same.
TEST(SettingsSchemaTest, FrontEndsSpellTheNamesAndKeepTheWords) {
    Settings s;
    s.reuse = true;
    s.cull = Cull::Oracle;
    const SettingsProblem problem = *settingsProblem(s);
    const std::string flags = describe(problem, s, [](const SettingInfo& info, const SettingValue& v) {
        return info.kind == SettingKind::Switch ? "--" + info.name : "--" + info.name + " " + settingText(info, v);
    });
    EXPECT_EQ(flags, "--reuse with --cull oracle: the oracle is an id pass of each frame, not a plan to reuse");
    const std::string one = describe(problem, s, [](const SettingInfo& info, const SettingValue& v) {
        return info.name == "reuse" ? std::string() : info.name + "=" + settingText(info, v);
    });
    EXPECT_EQ(one, "cull=oracle: the oracle is an id pass of each frame, not a plan to reuse");
}

// The trait tables: a method is known by what it needs, never by its name.
TEST(SettingsSchemaTest, TraitsSayWhatEachMethodNeeds) {
    EXPECT_TRUE(traitsOf(Cull::Paper).hull);
    EXPECT_FALSE(traitsOf(Cull::Paper).exact);
    EXPECT_EQ(std::count_if(kCullTraits.begin(), kCullTraits.end(), [](const CullTraits& t) { return t.hull; }), 1);
    EXPECT_TRUE(traitsOf(Cull::OcclusionAhead).occlusion && traitsOf(Cull::OcclusionAhead).ahead);
    EXPECT_TRUE(traitsOf(Cull::Oracle).idPass);
    EXPECT_FALSE(traitsOf(Cull::None).prepares);
    for (const Cull c : kCulls) EXPECT_EQ(fromString(toString(c), kCulls), c);
    EXPECT_EQ(namesOf(kOrders), "submit, key, paper, greedy, best");
    EXPECT_TRUE(traitsOf(Order::Greedy).measuresCosts);
    EXPECT_FALSE(traitsOf(Order::Key).measuresCosts);
    EXPECT_FALSE(traitsOf(Hsr::ZBuffer).plans);
}

}  // namespace
}  // namespace frugal
