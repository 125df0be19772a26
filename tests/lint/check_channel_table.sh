#!/usr/bin/env bash
# The README's channel table is the one the typed topics print
# (ubersim_channels --markdown): it fails, with the difference, when a topic
# or its row changed in code and not in the README, or the other way round.
# Usage: check_channel_table.sh SOURCE_DIR UBERSIM_CHANNELS
set -uo pipefail
readme=$1/README.md
printed=$("$2" --markdown) || { echo "check_channel_table: $2 --markdown failed"; exit 1; }
# The table and the paragraph printed under it (the DDS bridge's channels).
in_readme=$(awk '/^\| channel \| type \| publisher \| subscribers \| rate \|$/ { on = 1 }
                 on && !/^\|/ { after++ }
                 on && after == 3 { exit }
                 on { print }' "$readme")
if [ "$printed" != "$in_readme" ]; then
  echo "check_channel_table: README.md's channel table differs from ubersim_channels --markdown"
  echo "(fix the README with the printed table, or common/src/topics.cpp):"
  diff <(echo "$in_readme") <(echo "$printed")
  exit 1
fi
echo "check_channel_table: README.md's table is the printed one ($(echo "$printed" | wc -l) lines)"
