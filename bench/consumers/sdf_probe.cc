// Gazebo's URDF to SDFormat conversion, one verdict a line: reads paths on standard input and
// writes {"v": "."} or {"v": "R", "msg": ...} for each, as worker.py does. Built by harness.py
// with g++ against the installed libsdformat (Debian 12: libsdformat-dev, sdformat 12); never
// committed as a binary. It parses and checks (sdf::Root::Load), it loads no meshes.
#include <iostream>
#include <string>
#include <sdf/sdf.hh>

static std::string esc(const std::string &s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') { o += '\\'; o += c; }
    else if (c == '\n' || c == '\r' || c == '\t') o += ' ';
    else if (static_cast<unsigned char>(c) < 0x20) o += ' ';
    else o += c;
  }
  return o.substr(0, 300);
}

int main() {
  std::cout << "{\"version\": \"" << SDF_VERSION_FULL << "\"}" << std::endl;
  std::string path;
  while (std::getline(std::cin, path)) {
    if (path.empty()) continue;
    sdf::Root root;
    sdf::Errors errors = root.Load(path);
    if (errors.empty() && root.Model() == nullptr) {
      std::cout << "{\"v\": \"R\", \"msg\": \"no model\"}" << std::endl;
    } else if (errors.empty()) {
      std::cout << "{\"v\": \".\", \"msg\": \"\", \"links\": " << root.Model()->LinkCount()
                << "}" << std::endl;
    } else {
      std::cout << "{\"v\": \"R\", \"msg\": \"" << esc(errors[0].Message()) << "\"}" << std::endl;
    }
  }
  return 0;
}
