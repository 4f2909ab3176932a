// Stand-in for the Ptex library's header (a git submodule of pbrt-v4 with no
// Debian package): the declarations pbrt's textures.cpp uses, and a cache that
// finds no texture, so a scene with a "ptex" texture gets pbrt's own error
// naming the file and this reason, and renders nothing from it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>

namespace Ptex {

class String {
  public:
    String &operator=(const char *s) {
        s_ = s;
        return *this;
    }
    const char *c_str() const { return s_.c_str(); }
    friend std::ostream &operator<<(std::ostream &os, const String &s) { return os << s.s_; }

  private:
    std::string s_;
};

class PtexErrorHandler {
  public:
    virtual ~PtexErrorHandler() = default;
    virtual void reportError(const char *error) = 0;
};
class PtexInputHandler;

struct Info {
    int numFaces = 0;
};

class PtexTexture {
  public:
    int numChannels() const { return 0; }
    Info getInfo() const { return {}; }
    void release() {}
};

class PtexFilter {
  public:
    enum class FilterType { f_point, f_bilinear, f_box, f_gaussian, f_bicubic, f_bspline, f_catmullrom, f_mitchell };
    struct Options {
        explicit Options(FilterType) {}
    };
    static PtexFilter *getFilter(PtexTexture *, const Options &) { return nullptr; }
    void eval(float *, int, int, int, float, float, float, float, float, float) {}
    void release() {}
};

class PtexCache {
  public:
    struct Stats {
        uint64_t memUsed = 0, peakMemUsed = 0, filesOpen = 0, peakFilesOpen = 0,
                 filesAccessed = 0, fileReopens = 0, blockReads = 0;
    };
    static PtexCache *create(int, size_t, bool, PtexInputHandler *, PtexErrorHandler *) {
        static PtexCache cache;
        return &cache;
    }
    PtexTexture *get(const char *filename, String &error) {
        error = (std::string(filename) +
                 ": Ptex textures need the Ptex library, which this build of pbrt-v4 "
                 "(alignset's integrations/pbrt-v4) does not have").c_str();
        return nullptr;
    }
    void getStats(Stats &stats) { stats = Stats(); }
};

}  // namespace Ptex

using Ptex::PtexErrorHandler;
