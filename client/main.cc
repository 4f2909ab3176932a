#include <cstdio>
#include <cstring>
#include <string>

#include "client/commands.h"

namespace {

void PrintUsage() {
  std::fprintf(stderr,
               "usage: alignset <command> [options]\n"
               "\n"
               "commands:\n"
               "  optimize  --n N --dir DEG [--dir DEG] [--seed S] [--max-iterations K]\n"
               "            [--engine auto|direct|fast|cuda] [--threads T] [--learning-rate LR]\n"
               "            [--length L] [--width W] [--radius R] [--sw-weight C] [--anneal R]\n"
               "            [--revert-divisor D] --out FILE\n"
               "            optimize an aligned set (DEG: spectral direction = edge normal)\n"
               "  evaluate  FILE --normal DEG [--edges E] [--shifts K] [--seed S]\n"
               "            CP-rotated variance on parallel step edges and strip periodograms,\n"
               "            beside an Owen-scrambled Sobol set of the same N\n"
               "  sample    KIND --n N [--seed S] [--shear DEG] --out FILE\n"
               "            a set from a classic sampler ('alignset sample --list' names them)\n"
               "  align     FILE --canonical PHI --dir DEG [--canonical PHI2 --dir DEG2] --out FILE\n"
               "            align a canonical set onto requested directions (swap / invert)\n"
               "  variance  FILE... --normal DEG [--normal DEG] [--shifts K] [--seed S]\n"
               "            CP-rotated variance on step edges, one tab-separated line each\n");
#ifdef ALIGNSET_HAVE_STORAGE
  std::fprintf(stderr,
               "  cache     export|import|merge|verify|list ...\n"
               "            maintain SQLite cache files ('alignset cache help')\n");
#endif
#ifdef ALIGNSET_HAVE_SERVICE
  std::fprintf(stderr,
               "  get        --n N --dir DEG [--dir DEG] --out FILE [--quiet]\n"
               "             an aligned set from alignset-server (.npy or UTK text by extension)\n"
               "  precompute --n N[,N...] [--space 1dir|2dir|keys] [--key DEG[,DEG]] [--shard i/M]\n"
               "             fill the server's cache, with progress and ETA (re-run resumes)\n"
               "  stats      [--list [--n N] [--limit K]]\n"
               "             the server's cache contents and metrics\n"
               "  server options: --server ADDR (default $ALIGNSET_SERVER or 127.0.0.1:50051)\n"
               "             --tls-ca FILE --tls-server-name NAME --token-file FILE --timeout S\n");
#endif
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "help")) {
    PrintUsage();
    return argc < 2 ? 2 : 0;
  }
  const std::string cmd = argv[1];
  if (cmd == "optimize") return alignset::cli::RunOptimize(argc - 2, argv + 2);
  if (cmd == "evaluate") return alignset::cli::RunEvaluate(argc - 2, argv + 2);
  if (cmd == "sample") return alignset::cli::RunSample(argc - 2, argv + 2);
  if (cmd == "align") return alignset::cli::RunAlign(argc - 2, argv + 2);
  if (cmd == "variance") return alignset::cli::RunVariance(argc - 2, argv + 2);
#ifdef ALIGNSET_HAVE_STORAGE
  if (cmd == "cache") return alignset::cli::RunCache(argc - 2, argv + 2);
#endif
#ifdef ALIGNSET_HAVE_SERVICE
  if (cmd == "get") return alignset::cli::RunGet(argc - 2, argv + 2);
  if (cmd == "precompute") return alignset::cli::RunPrecompute(argc - 2, argv + 2);
  if (cmd == "stats") return alignset::cli::RunStats(argc - 2, argv + 2);
#endif
  std::fprintf(stderr, "alignset: unknown command '%s' (try 'alignset --help')\n", cmd.c_str());
  return 2;
}
