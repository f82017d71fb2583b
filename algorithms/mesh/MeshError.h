#pragma once
// The one error type for bad mesh input. Its message always names the file,
// where in it (line or element) and what is wrong, e.g.
//   "bunny.obj: line 12: face index 40 is out of range (the file has 38 vertices)".
#include <stdexcept>
#include <string>

namespace contour {

class MeshError : public std::runtime_error {
public:
    MeshError(std::string file, std::string location, std::string problem)
        : std::runtime_error(compose(file, location, problem)), file_(std::move(file)),
          location_(std::move(location)), problem_(std::move(problem)) {}

    const std::string& file() const { return file_; }
    const std::string& location() const { return location_; }
    const std::string& problem() const { return problem_; }

private:
    static std::string compose(const std::string& file, const std::string& location,
                               const std::string& problem) {
        return file + ": " + (location.empty() ? "" : location + ": ") + problem;
    }
    std::string file_, location_, problem_;
};

} // namespace contour
