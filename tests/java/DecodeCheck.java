// Decodes a vision frame written by the C++ side with the generated Java class,
// as lcm-spy does, and prints its fields: proves the jar lcm-spy loads decodes
// our messages.
import java.nio.file.Files;
import java.nio.file.Paths;

public class DecodeCheck {
    public static void main(String[] args) throws Exception {
        byte[] bytes = Files.readAllBytes(Paths.get(args[0]));
        ubersim.vision_frame_t frame = new ubersim.vision_frame_t(bytes);
        System.out.println("camera_id=" + frame.camera_id + " frame_number=" + frame.frame_number
                + " num_robots_blue=" + frame.num_robots_blue
                + " blue0_id=" + frame.robots_blue[0].robot_id
                + " blue0_x=" + frame.robots_blue[0].x);
    }
}
