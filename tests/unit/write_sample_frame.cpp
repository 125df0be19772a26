// Writes one encoded vision_frame_t to a file (for the Java decode test), or
// publishes it on VISION a few times a second (to look at in lcm-spy).
#include <chrono>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <ubersim/vision_frame_t.hpp>
#include <vector>

#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

int main(int argc, char** argv) {
  ubersim::vision_frame_t frame{};
  frame.camera_id = 3;
  frame.frame_number = 4242;
  frame.t_capture = 1.0;
  frame.t_sent = 1.1;
  frame.num_robots_blue = 1;
  frame.robots_blue = {{7, 0.9f, 1.25, -0.5, 0.3, 100, 200}};
  if (argc == 3 && std::string(argv[1]) == "--file") {
    std::vector<uint8_t> bytes(static_cast<size_t>(frame.getEncodedSize()));
    frame.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    std::ofstream(argv[2], std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
    return 0;
  }
  if (argc == 3 && std::string(argv[1]) == "--publish") {
    ubersim::MessageBus bus(ubersim::default_lcm_url());
    for (int i = 0; i < std::stoi(argv[2]); ++i) {
      frame.frame_number = 4242 + i;
      bus.publish("VISION", frame);
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    return 0;
  }
  std::cerr << "usage: write_sample_frame --file PATH | --publish COUNT\n";
  return 2;
}
