#pragma once
// The C types idlc generates from dds_bridge/idl/ubersim_msgs/*.idl, under
// short C++ names, and DdsType<T>: the topic descriptor of each.
#include <dds/dds.h>

#include "ubersim_msgs/geometry.h"
#include "ubersim_msgs/radio.h"
#include "ubersim_msgs/sim_control.h"
#include "ubersim_msgs/sim_state.h"
#include "ubersim_msgs/vision.h"

namespace ubersim::dds {

using DdsVisionBall = ubersim_msgs_msg_dds__VisionBall_;
using DdsVisionRobot = ubersim_msgs_msg_dds__VisionRobot_;
using DdsVisionFrame = ubersim_msgs_msg_dds__VisionFrame_;
using DdsFieldGeometry = ubersim_msgs_msg_dds__FieldGeometry_;
using DdsCameraCalibration = ubersim_msgs_msg_dds__CameraCalibration_;
using DdsVisionGeometry = ubersim_msgs_msg_dds__VisionGeometry_;
using DdsRobotCommand = ubersim_msgs_msg_dds__RobotCommand_;
using DdsRadioPacket = ubersim_msgs_msg_dds__RadioPacket_;
using DdsRobotFeedback = ubersim_msgs_msg_dds__RobotFeedback_;
using DdsRadioFeedback = ubersim_msgs_msg_dds__RadioFeedback_;
using DdsSimCommands = ubersim_msgs_msg_dds__SimCommands_;
using DdsBodyState = ubersim_msgs_msg_dds__BodyState_;
using DdsRobotState = ubersim_msgs_msg_dds__RobotState_;
using DdsSimState = ubersim_msgs_msg_dds__SimState_;
using DdsRobotPlacement = ubersim_msgs_msg_dds__RobotPlacement_;
using DdsBallPlacement = ubersim_msgs_msg_dds__BallPlacement_;
using DdsSimControl = ubersim_msgs_msg_dds__SimControl_;
using DdsSimControlAck = ubersim_msgs_msg_dds__SimControlAck_;

// The descriptor of each top-level (topic) type.
template <class T>
struct DdsType;

template <const dds_topic_descriptor_t* Descriptor>
struct DdsTypeWith {
  static const dds_topic_descriptor_t* descriptor() { return Descriptor; }
};

template <>
struct DdsType<DdsVisionFrame> : DdsTypeWith<&ubersim_msgs_msg_dds__VisionFrame__desc> {};
template <>
struct DdsType<DdsFieldGeometry> : DdsTypeWith<&ubersim_msgs_msg_dds__FieldGeometry__desc> {};
template <>
struct DdsType<DdsVisionGeometry> : DdsTypeWith<&ubersim_msgs_msg_dds__VisionGeometry__desc> {};
template <>
struct DdsType<DdsRadioPacket> : DdsTypeWith<&ubersim_msgs_msg_dds__RadioPacket__desc> {};
template <>
struct DdsType<DdsRadioFeedback> : DdsTypeWith<&ubersim_msgs_msg_dds__RadioFeedback__desc> {};
template <>
struct DdsType<DdsSimCommands> : DdsTypeWith<&ubersim_msgs_msg_dds__SimCommands__desc> {};
template <>
struct DdsType<DdsSimState> : DdsTypeWith<&ubersim_msgs_msg_dds__SimState__desc> {};
template <>
struct DdsType<DdsSimControl> : DdsTypeWith<&ubersim_msgs_msg_dds__SimControl__desc> {};
template <>
struct DdsType<DdsSimControlAck> : DdsTypeWith<&ubersim_msgs_msg_dds__SimControlAck__desc> {};

}  // namespace ubersim::dds
