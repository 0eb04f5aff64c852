// Verifying a directory of replays on worker threads (VerifyDir.h).
#include "lockbox/replay/VerifyDir.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <thread>

#include "lockbox/replay/Player.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox_cli/OptionReader.h"

namespace lockbox::replay {

namespace {

VerifyDirEntry VerifyOne(const std::filesystem::path& path, const GameRegistry& games,
                         const std::map<std::string, std::string>& options) {
    VerifyDirEntry e;
    e.name = path.filename().string();
    ReplayFile file;
    if (Error err = LoadReplay(path.string(), file); !err.ok()) {
        e.reason = err.Describe();
        return e;
    }
    std::string error;
    ToolGameRequest request{file, path.string(), options};
    std::unique_ptr<ToolGame> game = games.Make(request, error);
    if (!game) {
        e.reason = error.empty() ? "no game for \"" + file.gameName + "\"" : error;
        return e;
    }
    Player player(file, game->World(), game->Logic());
    const VerifyResult r = player.Verify();
    e.frames = r.frames;
    if (!r.error.ok()) {
        e.reason = r.error.Describe();
    } else if (r.ok) {
        e.outcome = VerifyDirEntry::Outcome::e_verified;
    } else {
        e.outcome = VerifyDirEntry::Outcome::e_diverged;
        e.firstBadFrame = r.firstBadFrame;
    }
    return e;
}

}  // namespace

bool VerifyDirectory(const std::string& dir, const GameRegistry& games, unsigned threads,
                     const std::map<std::string, std::string>& options, VerifyDirReport& out, std::string& error) {
    namespace fs = std::filesystem;
    std::error_code ec;
    std::vector<fs::path> files;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file() && it->path().extension() == ".lbr") files.push_back(it->path());
    if (ec) {
        error = dir + ": " + ec.message();
        return false;
    }
    // Name order: the report does not depend on the directory's order or the threads.
    std::sort(files.begin(), files.end(),
              [](const fs::path& a, const fs::path& b) { return a.filename().string() < b.filename().string(); });
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    threads = static_cast<unsigned>(std::min<size_t>(threads, std::max<size_t>(files.size(), 1)));
    std::vector<VerifyDirEntry> entries(files.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i = next++; i < files.size(); i = next++) entries[i] = VerifyOne(files[i], games, options);
    };
    std::vector<std::thread> workers;
    for (unsigned t = 1; t < threads; ++t) workers.emplace_back(work);
    work();
    for (std::thread& w : workers) w.join();
    VerifyDirReport report;
    for (const VerifyDirEntry& e : entries) {
        report.verified += e.outcome == VerifyDirEntry::Outcome::e_verified;
        report.diverged += e.outcome == VerifyDirEntry::Outcome::e_diverged;
        report.corrupt += e.outcome == VerifyDirEntry::Outcome::e_corrupt;
    }
    report.entries = std::move(entries);
    out = std::move(report);
    return true;
}

int RunVerifyDir(int argc, char** argv, const GameRegistry& games, const std::string& program) {
    cli::OptionReader args(program, argc, argv);
    std::string dir;
    unsigned jobs = 0;
    std::map<std::string, std::string> options;
    while (args.Next()) {
        if (args.Is("--jobs")) {
            args.Int(1, 1024, jobs);
            continue;
        }
        bool isOption = false;
        for (const GameRegistry::Option& o : games.Options()) {
            if (!args.Is(o.name)) continue;
            isOption = true;
            std::string value;
            if (args.Text(value)) options[o.name] = value;
        }
        if (isOption) continue;
        if (dir.empty() && !args.Current().empty() && args.Current().front() != '-')
            dir = std::string(args.Current());
        else
            args.Unknown();
    }
    if (!args.Failed() && dir.empty()) args.Refuse("verify-dir needs a directory");
    if (args.Failed()) return args.Fail((std::string("usage: ") + program + " " + kVerifyDirUsage + "\n").c_str());
    VerifyDirReport report;
    std::string error;
    if (!VerifyDirectory(dir, games, jobs, options, report, error)) {
        std::fprintf(stderr, "%s: %s\n", program.c_str(), error.c_str());
        return 2;
    }
    for (const VerifyDirEntry& e : report.entries) {
        switch (e.outcome) {
            case VerifyDirEntry::Outcome::e_verified:
                std::printf("%s: verified, %d frames\n", e.name.c_str(), e.frames);
                break;
            case VerifyDirEntry::Outcome::e_diverged:
                std::printf("%s: diverged at frame %d\n", e.name.c_str(), e.firstBadFrame);
                break;
            case VerifyDirEntry::Outcome::e_corrupt:
                std::printf("%s: corrupt: %s\n", e.name.c_str(), e.reason.c_str());
                break;
        }
    }
    std::printf("%zu replays: %zu verified, %zu diverged, %zu corrupt\n", report.entries.size(), report.verified,
                report.diverged, report.corrupt);
    return report.diverged + report.corrupt == 0 ? 0 : 1;
}

}  // namespace lockbox::replay
