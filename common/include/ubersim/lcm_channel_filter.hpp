#pragma once
// A kernel-side channel filter for LCM's multicast receive socket.
//
// LCM 1.3.1 (udpm) has every process on the group receive every datagram:
// its receive thread wakes, copies the datagram and only then finds that no
// handler subscribes to its channel. At 300-400 datagrams per second of sim
// time, that wakeup (20-30 us in a VM) is most of what ground truth and sync
// mode cost a process that wants a tenth of them. A classic BPF socket filter
// lets the kernel drop the rest before they are queued: no wakeup, no copy.
//
// The filter sees the datagram as a UDP socket filter does, UDP header first.
// It accepts a short LCM message ('LC02') whose channel is one of the names
// given, exactly, and every fragment ('LC03': only the first names its
// channel; the receiver decides); it drops everything else, which LCM would
// have dropped too (other channels, and datagrams without LCM's magic).
#include <linux/filter.h>

#include <set>
#include <string>
#include <vector>

namespace ubersim {

// True when LCM (which treats a subscription as a regular expression) would
// match `channel` as the plain name it is.
bool is_plain_channel_name(const std::string& channel);

// The program for `channels` (plain names, at most 63 characters each).
std::vector<sock_filter> lcm_channel_filter_program(const std::set<std::string>& channels);

// Replaces socket_fd's filter; false (and the socket left as it was) when the
// kernel refuses.
bool attach_lcm_channel_filter(int socket_fd, const std::set<std::string>& channels);
// Removes it (every datagram reaches the socket again).
void detach_lcm_channel_filter(int socket_fd);

}  // namespace ubersim
