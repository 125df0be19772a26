// The ROS 2 interface package for users (<build>/dds_bridge/generated/ros2/
// ubersim_msgs: package.xml and CMakeLists.txt from dds_bridge/ros2, the .msg
// files generated with the IDL from the .lcm files) must describe exactly the
// IDL the bridge is built from: same messages, same fields in the same order
// with the matching ROS types, same constants. ROS 2 generates
// ubersim_msgs::msg::dds_::<Name>_ from those .msg files, so this is what makes
// a ROS 2 node and the bridge agree on the wire. (The ROS spelling of each IDL
// type is written here a second time, on purpose: a check of the generator.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kGenerated = UBERSIM_DDS_GENERATED_DIR;  // from the .lcm files
const fs::path kPackage = kGenerated / "ros2" / "ubersim_msgs";

struct Message {
  std::vector<std::string> fields;     // "type name", ROS spelling
  std::vector<std::string> constants;  // "type NAME=value"
};

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string strip_comments(const std::string& text, const std::string& marker) {
  std::stringstream in(text);
  std::string out;
  std::string line;
  while (std::getline(in, line)) {
    const auto at = line.find(marker);
    out += (at == std::string::npos ? line : line.substr(0, at)) + "\n";
  }
  return out;
}

// An IDL type as ROS 2 writes it in a .msg.
std::string ros_type(std::string idl) {
  static const std::map<std::string, std::string> primitive{
      {"int8", "int8"},     {"int32", "int32"},  {"int64", "int64"},  {"double", "float64"},
      {"float", "float32"}, {"boolean", "bool"}, {"string", "string"}};
  const auto found = primitive.find(idl);
  if (found != primitive.end()) return found->second;
  const auto colon = idl.rfind("::");
  if (colon != std::string::npos) idl = idl.substr(colon + 2);
  if (!idl.empty() && idl.back() == '_') idl.pop_back();
  return idl;
}

std::map<std::string, Message> parse_idl() {
  std::map<std::string, Message> out;
  const std::regex structure(R"(struct\s+(\w+)_\s*\{([^}]*)\})");
  const std::regex member(R"((sequence<\s*([\w:]+)\s*>|[\w:]+)\s+(\w+)\s*(\[\s*(\d+)\s*\])?\s*;)");
  const std::regex constants(R"(module\s+(\w+)_Constants\s*\{([^}]*)\})");
  const std::regex constant(R"(const\s+(\w+)\s+(\w+)\s*=\s*(-?\d+)\s*;)");
  for (const auto& entry : fs::directory_iterator(kGenerated / "idl" / "ubersim_msgs")) {
    const std::string text = strip_comments(read(entry.path()), "//");
    for (auto s = std::sregex_iterator(text.begin(), text.end(), structure);
         s != std::sregex_iterator(); ++s) {
      Message& message = out[(*s)[1]];
      const std::string body = (*s)[2];
      for (auto m = std::sregex_iterator(body.begin(), body.end(), member);
           m != std::sregex_iterator(); ++m) {
        std::string type = (*m)[2].matched ? ros_type((*m)[2]) + "[]" : ros_type((*m)[1]);
        if ((*m)[5].matched) type += "[" + (*m)[5].str() + "]";
        message.fields.push_back(type + " " + (*m)[3].str());
      }
    }
    for (auto c = std::sregex_iterator(text.begin(), text.end(), constants);
         c != std::sregex_iterator(); ++c) {
      Message& message = out[(*c)[1]];
      const std::string body = (*c)[2];
      for (auto k = std::sregex_iterator(body.begin(), body.end(), constant);
           k != std::sregex_iterator(); ++k)
        message.constants.push_back(ros_type((*k)[1]) + " " + (*k)[2].str() + "=" + (*k)[3].str());
    }
  }
  return out;
}

std::map<std::string, Message> parse_msgs() {
  std::map<std::string, Message> out;
  const std::regex field(R"(^\s*([\w\[\]]+)\s+(\w+)\s*$)");
  const std::regex constant(R"(^\s*(\w+)\s+(\w+)\s*=\s*(-?\d+)\s*$)");
  for (const auto& entry : fs::directory_iterator(kPackage / "msg")) {
    Message& message = out[entry.path().stem().string()];
    std::stringstream lines(strip_comments(read(entry.path()), "#"));
    std::string line;
    std::smatch match;
    while (std::getline(lines, line)) {
      if (std::regex_match(line, match, constant)) {
        message.constants.push_back(match[1].str() + " " + match[2].str() + "=" + match[3].str());
      } else if (std::regex_match(line, match, field)) {
        message.fields.push_back(match[1].str() + " " + match[2].str());
      } else {
        EXPECT_TRUE(line.find_first_not_of(" \t") == std::string::npos)
            << entry.path() << ": cannot read '" << line << "'";
      }
    }
  }
  return out;
}

}  // namespace

TEST(Ros2Messages, MsgFilesMatchTheIdlFieldForField) {
  const auto idl = parse_idl();
  const auto msgs = parse_msgs();
  ASSERT_GE(idl.size(), 18u);  // every struct of the generated IDL was read
  for (const auto& [name, message] : idl) {
    const auto found = msgs.find(name);
    ASSERT_NE(found, msgs.end()) << "no ros2/ubersim_msgs/msg/" << name << ".msg";
    EXPECT_EQ(found->second.fields, message.fields) << name;
    EXPECT_EQ(found->second.constants, message.constants) << name;
  }
  for (const auto& [name, message] : msgs)
    EXPECT_EQ(idl.count(name), 1u) << name << ".msg has no IDL struct " << name << "_";
}

TEST(Ros2Messages, PackageGeneratesEveryMsgFile) {
  EXPECT_TRUE(fs::exists(kPackage / "package.xml"));
  const std::string cmake = read(kPackage / "CMakeLists.txt");
  EXPECT_NE(cmake.find("rosidl_generate_interfaces(${PROJECT_NAME} ${msg_files})"),
            std::string::npos);
  EXPECT_NE(cmake.find("msg/*.msg"), std::string::npos);
}
