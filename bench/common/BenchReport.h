#pragma once
/// Printing and file helpers shared by lockbox_bench and lockbox_accuracy: the contracted run
/// line, the profile block, the machine name for bench/results/<machine>/, and splicing a
/// generated block into a Markdown file between markers.

#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "BenchRunner.h"

namespace lockbox::scenes {

/// A time in ms as printed: four decimals, or six below 0.01 ms, where four would leave the
/// microsecond scenes (hello, the bullets) one or two significant digits.
inline std::string MsText(double ms) {
    char buf[32];
    std::snprintf(buf, sizeof buf, ms < 0.01 ? "%.6f" : "%.4f", ms);
    return buf;
}

/// The contracted one-line summary of a run.
inline void PrintLine(const RunResult& r) {
    std::printf(
        "scene=%s engine=%s steps=%d ms_per_step=%s p95_ms=%s bodies=%d awake=%d "
        "contacts=%d hash=0x%016" PRIx64 "%s\n",
        r.scene.c_str(), r.engine.c_str(), r.settings.steps, MsText(r.msPerStep).c_str(), MsText(r.p95Ms).c_str(),
        r.bodies, r.awake, r.contacts, r.hash, r.workers > 1 ? (" workers=" + std::to_string(r.workers)).c_str() : "");
}

/// The per-stage profile: wall-clock stages (ms per step) then work counters (per step).
inline void PrintProfile(const RunResult& r) {
    std::printf("  profile (per step, median over repeats):");
    for (const auto& [k, v] : r.profile)
        if (k.size() > 3 && k.compare(k.size() - 3, 3, "_ms") == 0) std::printf(" %s=%s", k.c_str(), MsText(v).c_str());
    std::printf("\n");
    bool any = false;
    for (const auto& [k, v] : r.profile) {
        if (k.rfind("n_", 0) != 0) continue;
        if (!any) std::printf("  work (per step):");
        any = true;
        std::printf(" %s=%.1f", k.c_str() + 2, v);
    }
    if (any) std::printf("\n");
}

/// A short machine name: the CPU model from /proc/cpuinfo, slugified, plus the core count
/// (e.g. "amd-epyc-7b13-2c"). A virtual machine may report only a vendor and a product line
/// ("AMD EPYC"), the same words for processors generations apart; a model name without a digit
/// then also carries the CPU family and model numbers ("amd-epyc-f26m2-2c"), so that two
/// generations do not file their results in one folder.
inline std::string MachineName() {
    std::ifstream in("/proc/cpuinfo");
    std::string line, model = "unknown-cpu", family, number;
    // The first processor's "model name", "cpu family" and "model" lines (keys end at the tab).
    while (std::getline(in, line) && !line.empty()) {
        const auto colon = line.find(':');
        if (colon == std::string::npos) continue;
        const std::string key = line.substr(0, line.find_first_of("\t:"));
        std::string value = line.substr(colon + 1);
        while (!value.empty() && value.front() == ' ') value.erase(value.begin());
        if (key == "model name") model = value;
        if (key == "cpu family") family = value;
        if (key == "model") number = value;
    }
    // Trademark marks and generic words carry no information about the machine.
    for (const char* noise : {"(R)", "(TM)", "(r)", "(tm)", "Processor", "CPU"}) {
        for (auto p = model.find(noise); p != std::string::npos; p = model.find(noise))
            model.erase(p, std::string(noise).size());
    }
    std::string slug;
    for (char c : model) {
        if (c == '@') break;  // the nominal clock adds nothing
        const bool alnum = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
        const bool upper = c >= 'A' && c <= 'Z';
        if (alnum)
            slug += c;
        else if (upper)
            slug += static_cast<char>(c - 'A' + 'a');
        else if (!slug.empty() && slug.back() != '-')
            slug += '-';
    }
    while (!slug.empty() && slug.back() == '-') slug.pop_back();
    const bool numbered = slug.find_first_of("0123456789") != std::string::npos;
    const auto digits = [](const std::string& s) {
        return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
    };
    if (!numbered && digits(family) && digits(number)) slug += "-f" + family + "m" + number;
    const unsigned cores = std::thread::hardware_concurrency();
    return slug + "-" + std::to_string(cores) + "c";
}

/// Replaces the text between `<!-- NAME:begin -->` and `<!-- NAME:end -->` in a Markdown file
/// with block (appending the markers, or creating the file with `title`, when absent).
inline bool SpliceMarkdown(const std::string& path, const std::string& name, const std::string& block,
                           const std::string& title) {
    std::string text;
    {
        std::ifstream in(path);
        if (in) {
            std::stringstream ss;
            ss << in.rdbuf();
            text = ss.str();
        } else {
            text = "# " + title + "\n\n";
        }
    }
    const std::string begin = "<!-- " + name + ":begin -->", end = "<!-- " + name + ":end -->";
    const auto b = text.find(begin), e = text.find(end);
    const std::string wrapped = begin + "\n" + block + end;
    if (b != std::string::npos && e != std::string::npos && e > b) {
        text.replace(b, e + end.size() - b, wrapped);
    } else {
        text += "\n" + wrapped + "\n";
    }
    std::ofstream out(path);
    out << text;
    return static_cast<bool>(out);
}

}  // namespace lockbox::scenes
