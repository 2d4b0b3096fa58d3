// A classifier's model file, read again only when it changes (modification time or size), so that a
// model retrained while the graph runs is picked up at the next frame. A file that cannot be read is
// not read again until it changes: its error is given on each frame meanwhile. DigitClassifier and
// Classifier hold their models this way.
#pragma once

#include <sys/stat.h>

#include <memory>
#include <stdexcept>
#include <string>

namespace apex_nodes {

template <class Model>
class ModelFile {
 public:
  /** @brief The model in `path`: `read(path)` (throwing std::invalid_argument) when the file is new
   *  or changed, else the one read before; `fresh` says whether this call read it. Throws
   *  std::invalid_argument naming the file when it is not there or cannot be read. */
  template <class Read>
  const Model& get(const std::string& path, const Read& read, bool& fresh) {
    fresh = false;
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
      model_.reset();
      throw std::invalid_argument("the model '" + path + "' cannot be read: no such file");
    }
    const Stamp stamp{path, st.st_mtim.tv_sec, st.st_mtim.tv_nsec, static_cast<long long>(st.st_size)};
    if (model_ && stamp == stamp_) return *model_;
    if (!failed_.empty() && stamp == stamp_) throw std::invalid_argument(failed_);
    model_.reset();  // a damaged file leaves no model behind
    failed_.clear();
    stamp_ = stamp;
    try {
      model_ = std::make_unique<Model>(read(path));
    } catch (const std::invalid_argument& e) {
      failed_ = e.what();
      throw;
    }
    fresh = true;
    return *model_;
  }

  /** @brief Reads the file again at the next get(), whatever its stamp (e.g. its parameter was set). */
  void forget() { model_.reset(), failed_.clear(), stamp_ = {}; }

 private:
  struct Stamp {
    std::string path;
    long sec = 0, nsec = 0;
    long long size = 0;
    bool operator==(const Stamp& o) const { return path == o.path && sec == o.sec && nsec == o.nsec && size == o.size; }
  };
  std::unique_ptr<Model> model_;
  Stamp stamp_;
  std::string failed_;  // why the file at stamp_ could not be read
};

}  // namespace apex_nodes
