#!/bin/sh
# The engine's rooms and the rooms each may include, so data flows one way (scene -> model ->
# solver -> result -> render/export): the engine never includes the server, physics and the solver
# never include the renderer, the renderer takes images and solve states but not the phantom or the
# coupling. Prints every include that breaks the map, and a room the map does not know; exits 1
# if there is any. Usage: room-includes.sh <engine directory>
engine=${1:?usage: room-includes.sh <engine directory>}

# Rooms (or single headers, room/File.hpp) a room may include besides its own.
allowed() {
  case $1 in
    math | image) echo "" ;;
    mesh) echo "math" ;;
    physics) echo "mesh math" ;;
    volume) echo "mesh math" ;;
    scene) echo "mesh volume math" ;;
    phantom) echo "mesh image volume math" ;;
    contact) echo "mesh scene math" ;;
    solver) echo "mesh physics scene contact math" ;;
    eval) echo "mesh physics scene contact solver phantom math" ;;
    planning) echo "mesh physics scene contact solver eval math" ;;
    render) echo "mesh scene eval image math solver/SimState.hpp" ;;
    *) echo "?" ;;
  esac
}

status=0
for dir in "$engine"/*/; do
  room=$(basename "$dir")
  rules=$(allowed "$room")
  if [ "$rules" = "?" ]; then
    echo "room $room: not in the map of tests/rooms/room-includes.sh"
    status=1
    continue
  fi
  # Quoted includes of the form "room/..." only; system headers use <...>.
  grep -rnoE '#include "[A-Za-z_]+/[^"]+"' --include=*.cpp --include=*.hpp "$dir" |
    while IFS= read -r hit; do
      target=${hit#*#include \"}
      target=${target%\"}
      other=${target%%/*}
      [ "$other" = "$room" ] && continue
      ok=0
      for rule in $rules; do
        if [ "$rule" = "$other" ] || [ "$rule" = "$target" ]; then ok=1; fi
      done
      [ $ok = 1 ] || echo "${hit%%:*}: $room includes $target"
    done | grep . && status=1
done
exit $status
