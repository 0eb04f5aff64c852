// lockbox_token: mints admission tokens for lockbox_server (for tests, and as the reference a
// studio's matchmaker follows: docs/deploy.md "Admission tokens").
//
//   lockbox_token keygen                     a new shared key, 64 hex digits
//   lockbox_token mint --key-file F --match N --slot S [--client C] [--ttl SECONDS]
//                      [--now UNIX] [--nonce N]
//                                            one token, 128 hex digits
//   lockbox_token inspect TOKEN_HEX          the token's fields (the signature is not checked)

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "lockbox_admission/TokenAuthority.h"
#include "lockbox_cli/OptionReader.h"

namespace {

constexpr const char* kUsage =
    "usage:\n"
    "  lockbox_token keygen\n"
    "      prints a new random shared key (64 hex digits); give it to the matchmaker and to\n"
    "      lockbox_server (--token-key-file)\n"
    "  lockbox_token mint --key-file FILE --match ID --slot SLOT [options]\n"
    "      prints a signed admission token (128 hex digits)\n"
    "      --key-file FILE  file holding the shared key (64 hex digits)\n"
    "      --match ID       match id, 0 .. 4294967295\n"
    "      --slot SLOT      slot the client plays, 0 .. 63\n"
    "      --client ID      the matchmaker's id of the player (default 0)\n"
    "      --ttl SECONDS    lifetime, 1 .. 86400 (default 60)\n"
    "      --now UNIX       the current time in seconds since the epoch (default: the clock)\n"
    "      --nonce N        the nonce (default: random; fix it only in tests)\n"
    "  lockbox_token inspect TOKEN_HEX\n"
    "      prints the token's fields; the signature is not checked\n";

int Keygen(int argc, char** argv) {
    lockbox::cli::OptionReader args("lockbox_token", argc - 1, argv + 1);
    while (args.Next()) args.Unknown();
    if (args.Failed()) return args.Fail(kUsage);
    std::printf("%s\n", lockbox::admission::KeyHex(lockbox::admission::NewKey()).c_str());
    return 0;
}

int Mint(int argc, char** argv) {
    lockbox::cli::OptionReader args("lockbox_token", argc - 1, argv + 1);
    std::string keyFile;
    lockbox::admission::AdmissionToken token;
    bool haveMatch = false, haveSlot = false, haveNow = false, haveNonce = false;
    uint64_t ttl = 60, now = 0, nonce = 0;
    while (args.Next()) {
        if (args.Is("--key-file"))
            args.Text(keyFile);
        else if (args.Is("--match"))
            haveMatch = args.Int(0, 4294967295LL, token.matchId);
        else if (args.Is("--slot"))
            haveSlot = args.Int(0, 63, token.slot);
        else if (args.Is("--client"))
            args.Uint64(token.clientId);
        else if (args.Is("--ttl"))
            args.Int(1, 86400, ttl);
        else if (args.Is("--now"))
            haveNow = args.Uint64(now);
        else if (args.Is("--nonce"))
            haveNonce = args.Uint64(nonce);
        else
            args.Unknown();
    }
    if (!args.Failed() && keyFile.empty()) args.Refuse("mint needs --key-file");
    if (!args.Failed() && !haveMatch) args.Refuse("mint needs --match");
    if (!args.Failed() && !haveSlot) args.Refuse("mint needs --slot");
    if (args.Failed()) return args.Fail(kUsage);
    std::ifstream in(keyFile);
    std::stringstream text;
    text << in.rdbuf();
    const auto key = lockbox::admission::ParseKeyHex(text.str());
    if (!in || !key) {
        std::fprintf(stderr, "lockbox_token: %s does not hold a key (64 hex digits)\n", keyFile.c_str());
        return 2;
    }
    if (!haveNow)
        now = static_cast<uint64_t>(
            std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
                .count());
    token.expiresAt = now + ttl;
    token.nonce = haveNonce ? nonce : lockbox::admission::NewNonce();
    const auto bytes = lockbox::admission::TokenSigner(*key).Sign(token);
    std::printf("%s\n", lockbox::admission::ToHex(bytes).c_str());
    return 0;
}

int Inspect(int argc, char** argv) {
    lockbox::cli::OptionReader args("lockbox_token", argc - 1, argv + 1);
    std::string hex;
    while (args.Next()) {
        if (hex.empty() && !args.Current().empty() && args.Current().front() != '-')
            hex = std::string(args.Current());
        else
            args.Unknown();
    }
    if (!args.Failed() && hex.empty()) args.Refuse("inspect needs a token");
    if (args.Failed()) return args.Fail(kUsage);
    std::vector<uint8_t> bytes;
    lockbox::admission::AdmissionToken token;
    if (!lockbox::admission::FromHex(hex, bytes)) {
        std::fprintf(stderr, "lockbox_token: the token is not hexadecimal\n");
        return 1;
    }
    const auto error = lockbox::net::admission::ParseToken(bytes, token);
    if (error != lockbox::net::admission::TokenFormatError::e_ok) {
        std::fprintf(stderr, "lockbox_token: not a token: %s\n",
                     std::string(lockbox::net::admission::TokenFormatErrorName(error)).c_str());
        return 1;
    }
    std::printf("match %u\nslot %u\nclient %llu\nexpires %llu\nnonce %llu\n", token.matchId, token.slot,
                static_cast<unsigned long long>(token.clientId), static_cast<unsigned long long>(token.expiresAt),
                static_cast<unsigned long long>(token.nonce));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string command = argc > 1 ? argv[1] : "";
    if (command == "keygen") return Keygen(argc, argv);
    if (command == "mint") return Mint(argc, argv);
    if (command == "inspect") return Inspect(argc, argv);
    if (command == "--help" || command == "-h") {
        std::fputs(kUsage, stdout);
        return 0;
    }
    std::fprintf(stderr, "lockbox_token: %s\n%s",
                 command.empty() ? "a command is needed" : ("unknown command '" + command + "'").c_str(), kUsage);
    return 2;
}
