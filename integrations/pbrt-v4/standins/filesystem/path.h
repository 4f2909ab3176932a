// Stand-in for wjakob/filesystem's path class (a git submodule of pbrt-v4 with
// no Debian package), on std::filesystem: the members pbrt's util/file.cpp uses,
// with that library's meanings (extension() without its dot, parent_path() of a
// bare file name empty).
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

namespace filesystem {

class path {
  public:
    path() = default;
    path(const std::string &s) : p_(s) {}
    path(const char *s) : p_(s) {}
    path(std::filesystem::path p) : p_(std::move(p)) {}

    bool empty() const { return p_.empty(); }
    bool is_absolute() const { return p_.is_absolute(); }
    bool exists() const {
        std::error_code ec;
        return std::filesystem::exists(p_, ec);
    }
    bool is_directory() const {
        std::error_code ec;
        return std::filesystem::is_directory(p_, ec);
    }
    path parent_path() const { return path(p_.parent_path()); }
    std::string extension() const {
        std::string e = p_.extension().string();
        return e.empty() ? e : e.substr(1);
    }
    std::string filename() const { return p_.filename().string(); }
    path make_absolute() const {
        std::error_code ec;
        std::filesystem::path a = std::filesystem::absolute(p_, ec);
        return path(ec ? p_ : a.lexically_normal());
    }
    std::string str() const { return p_.string(); }
    path operator/(const path &other) const { return path(p_ / other.p_); }

  private:
    std::filesystem::path p_;
};

}  // namespace filesystem
