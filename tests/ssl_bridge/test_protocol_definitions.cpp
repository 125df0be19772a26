// Our .proto files against the official SSL definitions: every message, field
// and enum value of the official files (data/upstream_fields.txt, extracted
// from the upstream repositories at the commits named there) exists in our
// generated classes with the same name, number, label and type, and nothing
// more; then every field of every message survives a serialise/parse round trip.
#include <google/protobuf/any.pb.h>
#include <google/protobuf/descriptor.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/util/message_differencer.h>
#include <grSim_Packet.pb.h>
#include <grSim_Robotstatus.pb.h>
#include <gtest/gtest.h>
#include <messages_robocup_ssl_wrapper.pb.h>
#include <ssl_gc_ci.pb.h>
#include <ssl_simulation_control.pb.h>
#include <ssl_simulation_custom_erforce_realism.pb.h>
#include <ssl_simulation_custom_erforce_robot_spec.pb.h>
#include <ssl_simulation_robot_control.pb.h>
#include <ssl_simulation_robot_feedback.pb.h>
#include <ssl_vision_wrapper_tracked.pb.h>

#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using google::protobuf::Descriptor;
using google::protobuf::DescriptorPool;
using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

struct OfficialField {
  std::string message;
  int number = 0;
  std::string name;
  std::string label;
  std::string type;
};

struct OfficialDefinitions {
  std::vector<OfficialField> fields;
  std::vector<std::tuple<std::string, int, int>> reserved;  // message, start, end (exclusive)
  std::vector<std::tuple<std::string, int, std::string>> enum_values;
  std::set<std::string> messages;
};

OfficialDefinitions load_official() {
  std::ifstream in(UBERSIM_UPSTREAM_FIELDS);
  EXPECT_TRUE(in.good()) << UBERSIM_UPSTREAM_FIELDS;
  OfficialDefinitions out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    if (kind == "message") {
      OfficialField f;
      words >> f.message >> f.number >> f.name >> f.label >> f.type;
      out.messages.insert(f.message);
      out.fields.push_back(f);
    } else if (kind == "reserved") {
      std::string message;
      int start = 0, end = 0;
      words >> message >> start >> end;
      out.reserved.emplace_back(message, start, end);
    } else if (kind == "enum") {
      std::string name, value;
      int number = 0;
      words >> name >> number >> value;
      out.enum_values.emplace_back(name, number, value);
    } else {
      ADD_FAILURE() << "unknown line: " << line;
    }
  }
  return out;
}

// Makes sure every generated file is linked in (and so in the generated pool).
void link_all_files() {
  (void)SSL_WrapperPacket::descriptor();
  (void)TrackerWrapperPacket::descriptor();
  (void)SimulatorCommand::descriptor();
  (void)SimulatorResponse::descriptor();
  (void)RobotControl::descriptor();
  (void)RobotControlResponse::descriptor();
  (void)RealismConfigErForce::descriptor();
  (void)RobotSpecErForce::descriptor();
  (void)CiInput::descriptor();  // and through it every file of the GC's CI port
  (void)Output::descriptor();
  (void)grSim_Packet::descriptor();  // and grSim_Commands, grSim_Replacement
  (void)Robots_Status::descriptor();
}

const char* label_name(const FieldDescriptor& field) {
  if (field.is_repeated()) return "repeated";
  return field.is_required() ? "required" : "optional";
}

std::string type_name(const FieldDescriptor& field) {
  if (field.message_type() != nullptr) return field.message_type()->name();
  if (field.enum_type() != nullptr) return field.enum_type()->name();
  return field.type_name();
}

// Our own .proto files, as named in the generated pool.
const std::vector<std::string> kOurFiles = {
    "messages_robocup_ssl_detection.proto",
    "messages_robocup_ssl_geometry.proto",
    "messages_robocup_ssl_wrapper.proto",
    "ssl_gc_common.proto",
    "ssl_gc_geometry.proto",
    "ssl_vision_detection_tracked.proto",
    "ssl_vision_wrapper_tracked.proto",
    "ssl_simulation_config.proto",
    "ssl_simulation_control.proto",
    "ssl_simulation_error.proto",
    "ssl_simulation_robot_control.proto",
    "ssl_simulation_robot_feedback.proto",
    "ssl_simulation_custom_erforce_realism.proto",
    "ssl_simulation_custom_erforce_robot_spec.proto",
    "ssl_gc_game_event.proto",
    "ssl_gc_referee_message.proto",
    "ssl_gc_state.proto",
    "ssl_gc_change.proto",
    "ssl_gc_engine.proto",
    "ssl_gc_engine_config.proto",
    "ssl_gc_api.proto",
    "ssl_gc_ci.proto",
    "grSim_Packet.proto",
    "grSim_Commands.proto",
    "grSim_Replacement.proto",
    "grSim_Robotstatus.proto",
};

TEST(SslProtocolDefinitions, EveryOfficialFieldExistsWithTheSameNameNumberLabelAndType) {
  link_all_files();
  const OfficialDefinitions official = load_official();
  ASSERT_GT(official.fields.size(), 200u);
  const DescriptorPool* pool = DescriptorPool::generated_pool();
  std::map<std::string, int> official_field_count;
  for (const OfficialField& f : official.fields) {
    ++official_field_count[f.message];
    const Descriptor* message = pool->FindMessageTypeByName(f.message);
    ASSERT_NE(message, nullptr) << f.message;
    const FieldDescriptor* field = message->FindFieldByNumber(f.number);
    ASSERT_NE(field, nullptr) << f.message << " field " << f.number;
    EXPECT_EQ(field->name(), f.name) << f.message << " field " << f.number;
    EXPECT_EQ(label_name(*field), f.label) << f.message << "." << f.name;
    EXPECT_EQ(type_name(*field), f.type) << f.message << "." << f.name;
  }
  for (const auto& [name, start, end] : official.reserved) {
    const Descriptor* message = pool->FindMessageTypeByName(name);
    ASSERT_NE(message, nullptr) << name;
    for (int number = start; number < end; ++number) {
      EXPECT_TRUE(message->IsReservedNumber(number)) << name << " reserves " << number;
    }
  }
  for (const auto& [name, number, value] : official.enum_values) {
    const auto* type = pool->FindEnumTypeByName(name);
    ASSERT_NE(type, nullptr) << name;
    const auto* found = type->FindValueByNumber(number);
    ASSERT_NE(found, nullptr) << name << " " << number;
    EXPECT_EQ(found->name(), value) << name << " " << number;
  }
  // Nothing of our own invented in these files: every message is official
  // and has no field the official one lacks.
  for (const std::string& file_name : kOurFiles) {
    const auto* file = pool->FindFileByName(file_name);
    ASSERT_NE(file, nullptr) << file_name;
    for (int i = 0; i < file->message_type_count(); ++i) {
      const Descriptor* message = file->message_type(i);
      EXPECT_EQ(official.messages.count(message->name()), 1u)
          << message->name() << " in " << file_name << " is not an official message";
      EXPECT_EQ(message->field_count(), official_field_count[message->name()]) << message->name();
    }
  }
}

// A value for each field that differs from every default and from the other
// fields', so a field mixed up with another cannot compare equal.
void fill(Message& message, int variant, int depth);

void fill_one(Message& message, const FieldDescriptor& field, int variant, int depth) {
  const Reflection& r = *message.GetReflection();
  const int n = field.number();
  const bool repeated = field.is_repeated();
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_INT32:
      repeated ? r.AddInt32(&message, &field, -100 - n) : r.SetInt32(&message, &field, -100 - n);
      break;
    case FieldDescriptor::CPPTYPE_INT64:
      repeated ? r.AddInt64(&message, &field, 5'000'000'000LL + n)
               : r.SetInt64(&message, &field, 5'000'000'000LL + n);
      break;
    case FieldDescriptor::CPPTYPE_UINT32:
      repeated ? r.AddUInt32(&message, &field, 4'000'000'000U + n)
               : r.SetUInt32(&message, &field, 4'000'000'000U + n);
      break;
    case FieldDescriptor::CPPTYPE_UINT64:
      repeated ? r.AddUInt64(&message, &field, 9'000'000'000ULL + n)
               : r.SetUInt64(&message, &field, 9'000'000'000ULL + n);
      break;
    case FieldDescriptor::CPPTYPE_FLOAT:
      repeated ? r.AddFloat(&message, &field, 0.25f + n) : r.SetFloat(&message, &field, 0.25f + n);
      break;
    case FieldDescriptor::CPPTYPE_DOUBLE:
      repeated ? r.AddDouble(&message, &field, 1e9 + n + 0.125)
               : r.SetDouble(&message, &field, 1e9 + n + 0.125);
      break;
    case FieldDescriptor::CPPTYPE_BOOL:
      // the opposite of the default, so it is written even when explicit
      repeated ? r.AddBool(&message, &field, true)
               : r.SetBool(&message, &field, !field.default_value_bool());
      break;
    case FieldDescriptor::CPPTYPE_ENUM: {
      const auto* type = field.enum_type();
      const auto* value = type->value(type->value_count() - 1);  // never the default 0
      repeated ? r.AddEnum(&message, &field, value) : r.SetEnum(&message, &field, value);
      break;
    }
    case FieldDescriptor::CPPTYPE_STRING: {
      const std::string text = field.name() + "-" + std::to_string(n);
      repeated ? r.AddString(&message, &field, text) : r.SetString(&message, &field, text);
      break;
    }
    case FieldDescriptor::CPPTYPE_MESSAGE: {
      Message* child =
          repeated ? r.AddMessage(&message, &field) : r.MutableMessage(&message, &field);
      if (field.message_type()->full_name() == "google.protobuf.Any") {
        RobotSpecErForce spec;
        spec.set_shoot_radius(0.08f + 0.001f * static_cast<float>(n));
        spec.set_dribbler_width(0.05f);
        google::protobuf::Any any;
        any.PackFrom(spec);
        child->CopyFrom(any);
      } else {
        fill(*child, variant, depth + 1);
      }
      break;
    }
  }
}

// The game controller's state and change messages nest deeper than the
// vision and simulation ones (StateChange > State > TeamInfo > YellowCard >
// GameEvent > ...), and GameEvent.MultipleFouls holds GameEvents: below this
// depth repeated messages are left empty (singular ones, which may have
// required fields, are still filled).
constexpr int kMaxDepth = 8;

void fill(Message& message, int variant, int depth) {
  const Descriptor& type = *message.GetDescriptor();
  for (int i = 0; i < type.field_count(); ++i) {
    const FieldDescriptor& field = *type.field(i);
    if (const auto* oneof = field.containing_oneof()) {
      // One member per oneof: the variant chooses which.
      if (oneof->field(variant % oneof->field_count()) != &field) continue;
    }
    if (depth >= kMaxDepth && field.is_repeated() && field.message_type() != nullptr) continue;
    // Two entries of a map would have the same key: one.
    const int copies = field.is_repeated() && !field.is_map() ? 2 : 1;
    for (int c = 0; c < copies; ++c) fill_one(message, field, variant, depth);
  }
}

int max_oneof_size(const Descriptor& type, int depth = 0) {
  int most = 1;
  if (depth > kMaxDepth) return most;
  for (int i = 0; i < type.oneof_decl_count(); ++i)
    most = std::max(most, type.oneof_decl(i)->field_count());
  for (int i = 0; i < type.field_count(); ++i) {
    const Descriptor* child = type.field(i)->message_type();
    if (child != nullptr) most = std::max(most, max_oneof_size(*child, depth + 1));
  }
  return most;
}

TEST(SslProtocolDefinitions, EveryFieldOfEveryMessageRoundTrips) {
  link_all_files();
  const OfficialDefinitions official = load_official();
  const DescriptorPool* pool = DescriptorPool::generated_pool();
  auto* factory = google::protobuf::MessageFactory::generated_factory();
  int round_trips = 0;
  for (const std::string& name : official.messages) {
    const Descriptor* type = pool->FindMessageTypeByName(name);
    ASSERT_NE(type, nullptr) << name;
    for (int variant = 0; variant < max_oneof_size(*type); ++variant) {
      std::unique_ptr<Message> original(factory->GetPrototype(type)->New());
      fill(*original, variant, 0);
      ASSERT_TRUE(original->IsInitialized()) << name;
      std::string bytes;
      ASSERT_TRUE(original->SerializeToString(&bytes)) << name;
      std::unique_ptr<Message> decoded(factory->GetPrototype(type)->New());
      ASSERT_TRUE(decoded->ParseFromString(bytes)) << name;
      std::string difference;
      google::protobuf::util::MessageDifferencer differencer;
      differencer.ReportDifferencesToString(&difference);
      EXPECT_TRUE(differencer.Compare(*original, *decoded)) << name << ": " << difference;
      // Every field that was set is set after the trip (not only equal by default).
      std::vector<const FieldDescriptor*> before, after;
      original->GetReflection()->ListFields(*original, &before);
      decoded->GetReflection()->ListFields(*decoded, &after);
      EXPECT_EQ(before, after) << name;
      ++round_trips;
    }
  }
  EXPECT_GE(round_trips, static_cast<int>(official.messages.size()));
}

TEST(SslProtocolDefinitions, ErForceCustomMessagesTravelInsideAny) {
  RealismConfigErForce realism;
  realism.set_stddev_robot_p(0.003f);
  realism.set_vision_delay(35'000'000);
  SimulatorCommand command;
  command.mutable_config()->mutable_realism_config()->add_custom()->PackFrom(realism);
  RobotSpecs* specs = command.mutable_config()->add_robot_specs();
  specs->mutable_id()->set_id(3);
  specs->mutable_id()->set_team(BLUE);
  specs->set_center_to_dribbler(0.075f);
  RobotSpecErForce erforce;
  erforce.set_shoot_radius(0.067f);
  specs->add_custom()->PackFrom(erforce);

  SimulatorCommand decoded;
  ASSERT_TRUE(decoded.ParseFromString(command.SerializeAsString()));
  const auto& any_realism = decoded.config().realism_config().custom(0);
  EXPECT_EQ(any_realism.type_url(), "type.googleapis.com/RealismConfigErForce");
  RealismConfigErForce realism_back;
  ASSERT_TRUE(any_realism.UnpackTo(&realism_back));
  EXPECT_FLOAT_EQ(realism_back.stddev_robot_p(), 0.003f);
  EXPECT_EQ(realism_back.vision_delay(), 35'000'000);
  const RobotSpecs& specs_back = decoded.config().robot_specs(0);
  EXPECT_FLOAT_EQ(specs_back.center_to_dribbler(), 0.075f);
  EXPECT_EQ(specs_back.custom(0).type_url(), "type.googleapis.com/RobotSpecErForce");
  RobotSpecErForce erforce_back;
  ASSERT_TRUE(specs_back.custom(0).UnpackTo(&erforce_back));
  EXPECT_FLOAT_EQ(erforce_back.shoot_radius(), 0.067f);
}

}  // namespace
