// A small mutation fuzzer for LLVMFuzzerTestOneInput targets, for builds without libFuzzer.
// It is not coverage-guided: it applies random byte-level and token-level mutations to the
// target's seeds for a bounded number of runs or seconds. Its job in the test suite is to prove
// that no input crashes an importer (run under ASan+UBSan in the sanitizer build).
//   usage: fuzz_x [--seconds S] [--runs N] [--seed K] [FILE...]   (FILEs: extra seeds / repro)
// Without --seed each run draws its own and prints it first, so that a run that finds a crash is
// repeated exactly by passing that seed.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_seeds.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

const char* const kTokens[] = {"0", "-1", "1e308", "-1e308", "nan", "inf", "1e-320", "99999999999",
                               "{", "}", "[", "]", ",", ":", "\n", " ", "\"", "-", ".", "#",
                               "2147483648", "-0", "0x10", "\t", "---", "null", "true"};

std::string mutate(std::string s, const std::vector<std::string>& seeds, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const std::size_t rounds = 1 + pick(6);
  for (std::size_t r = 0; r < rounds; ++r) {
    switch (pick(9)) {
      case 0:  // flip a byte
        if (!s.empty()) s[pick(s.size())] = static_cast<char>(pick(256));
        break;
      case 1:  // insert a token
        s.insert(pick(s.size() + 1), kTokens[pick(sizeof kTokens / sizeof *kTokens)]);
        break;
      case 2: {  // erase a range
        if (s.empty()) break;
        const std::size_t at = pick(s.size());
        s.erase(at, 1 + pick(std::min<std::size_t>(64, s.size() - at)));
        break;
      }
      case 3:  // truncate
        s.resize(pick(s.size() + 1));
        break;
      case 4: {  // duplicate a range
        if (s.empty()) break;
        const std::size_t at = pick(s.size());
        const std::string piece = s.substr(at, 1 + pick(200));
        s.insert(pick(s.size() + 1), piece);
        break;
      }
      case 5: {  // replace a number-ish token with another token
        if (s.empty()) break;
        std::size_t at = pick(s.size());
        while (at < s.size() && !(std::isdigit(static_cast<unsigned char>(s[at])) || s[at] == '-')) ++at;
        std::size_t end = at;
        while (end < s.size() && (std::isdigit(static_cast<unsigned char>(s[end])) || s[end] == '.' || s[end] == '-' || s[end] == 'e')) ++end;
        s.replace(at, end - at, kTokens[pick(sizeof kTokens / sizeof *kTokens)]);
        break;
      }
      case 6: {  // splice with another seed
        if (seeds.empty()) break;
        const std::string& other = seeds[pick(seeds.size())];
        const std::size_t cut = pick(s.size() + 1), from = pick(other.size() + 1);
        s = s.substr(0, cut) + other.substr(from);
        break;
      }
      case 7: {  // swap two lines
        std::vector<std::string> lines;
        std::stringstream ss(s);
        for (std::string l; std::getline(ss, l);) lines.push_back(l);
        if (lines.size() < 2) break;
        std::swap(lines[pick(lines.size())], lines[pick(lines.size())]);
        s.clear();
        for (const auto& l : lines) s += l + "\n";
        break;
      }
      default:  // delete one line
        if (const auto nl = s.find('\n', pick(s.size() + 1)); nl != std::string::npos) {
          const auto next = s.find('\n', nl + 1);
          s.erase(nl, next == std::string::npos ? std::string::npos : next - nl);
        }
        break;
    }
    if (s.size() > (1u << 22)) s.resize(1u << 22);
  }
  return s;
}

// The input being run, written to fuzz-failure.bin in the working directory when the run dies (an
// uncaught exception ends in abort; a sanitizer report ends in its death callback), so that the
// crash can be replayed as `fuzz_x fuzz-failure.bin` without re-running the mutations.
const std::string* g_current = nullptr;

void save_current_input() {
  if (g_current == nullptr) return;
  const int fd = ::open("fuzz-failure.bin", O_WRONLY | O_CREAT | O_TRUNC, 0644);  // async-signal-safe
  if (fd < 0) return;
  std::size_t done = 0;
  while (done < g_current->size()) {
    const ssize_t n = ::write(fd, g_current->data() + done, g_current->size() - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  static const char kSaved[] = "fuzz: the failing input is in fuzz-failure.bin (replay: fuzz_x fuzz-failure.bin)\n";
  (void)!::write(2, kSaved, sizeof kSaved - 1);
  g_current = nullptr;
}

extern "C" void on_fatal_signal(int sig) {
  save_current_input();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

bool run_one(const std::string& s) {
  g_current = &s;
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(s.data()), s.size());
  g_current = nullptr;
  return true;
}

}  // namespace

extern "C" void __sanitizer_set_death_callback(void (*)(void)) __attribute__((weak));

int main(int argc, char** argv) {
  double seconds = 10.0;
  long runs = 100000;
  unsigned long seed = 0;
  bool seeded = false;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seconds" && i + 1 < argc) seconds = std::atof(argv[++i]);
    else if (a == "--runs" && i + 1 < argc) runs = std::atol(argv[++i]);
    else if (a == "--seed" && i + 1 < argc) seed = std::strtoul(argv[++i], nullptr, 10), seeded = true;
    else if (a.rfind("-", 0) == 0) { std::fprintf(stderr, "unknown option %s\n", a.c_str()); return 2; }
    else files.push_back(a);
  }
  if (!seeded) seed = std::random_device{}() ^ static_cast<unsigned long>(std::chrono::steady_clock::now().time_since_epoch().count());
  std::printf("fuzz: mutation seed %lu (repeat with --seed %lu)\n", seed, seed);
  std::fflush(stdout);
  for (const int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) std::signal(sig, on_fatal_signal);
  if (__sanitizer_set_death_callback != nullptr) __sanitizer_set_death_callback(save_current_input);
  std::vector<std::string> seeds = MimicFuzzSeeds();
  for (const std::string& f : files) {
    std::ifstream in(f, std::ios::binary);
    if (!in) { std::fprintf(stderr, "cannot read %s\n", f.c_str()); return 2; }
    std::stringstream ss;
    ss << in.rdbuf();
    seeds.push_back(ss.str());
  }
  seeds.emplace_back();
  for (const std::string& s : seeds) run_one(s);  // every seed as is, first
  std::mt19937_64 rng(seed);
  const auto start = std::chrono::steady_clock::now();
  long n = 0;
  for (; n < runs; ++n) {
    if ((n & 63) == 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds) break;
    const std::string& base = seeds[std::uniform_int_distribution<std::size_t>(0, seeds.size() - 1)(rng)];
    run_one(mutate(base, seeds, rng));
  }
  std::printf("fuzz: %ld mutated inputs from %zu seeds in %.1f s, no crash\n", n, seeds.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return 0;
}
