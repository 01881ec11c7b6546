#!/bin/sh
# The rooms of the engine or of the server and the rooms each may include, so data flows one way.
# Engine (scene -> model -> solver -> result -> render/export): the engine never includes the
# server, physics and the solver never include the renderer, the renderer takes images and solve
# states but not the phantom or the coupling. Server (cli -> net -> session -> schedule -> jobs ->
# cases -> util): the commands assemble the network, the network serves sessions, sessions run
# their work on the schedule's threads and queue jobs, jobs solve cases; each room may include
# the engine's rooms. Prints every include that breaks the map, and a room the map does not know;
# exits 1 if there is any.
# Usage: room-includes.sh <engine directory> | room-includes.sh --server <server directory>
if [ "$1" = "--server" ]; then
  kind=server
  shift
else
  kind=engine
fi
root=${1:?usage: room-includes.sh [--server] <directory>}

# Rooms (or single headers, room/File.hpp) a room may include besides its own.
allowed() {
  if [ $kind = server ]; then
    case $1 in
      util) echo "" ;;
      cases) echo "util" ;;
      jobs) echo "cases util" ;;
      schedule) echo "jobs cases util" ;;
      session) echo "schedule jobs cases util" ;;
      net) echo "session schedule jobs cases util" ;;
      cli) echo "net session schedule jobs cases util" ;;
      *) echo "?" ;;
    esac
    return
  fi
  case $1 in
    math | image | system) echo "" ;;
    mesh) echo "system math" ;;
    meshing | io) echo "mesh math" ;;
    physics) echo "mesh system math" ;;
    volume) echo "mesh io math" ;;
    scene) echo "mesh meshing io system volume math" ;;
    phantom) echo "mesh meshing io system image volume math" ;;
    contact) echo "mesh scene physics math" ;;
    solver) echo "mesh physics scene contact system math" ;;
    eval) echo "mesh physics scene contact solver phantom system math" ;;
    planning) echo "mesh physics scene contact solver eval math" ;;
    render) echo "mesh io scene eval image math solver/SimState.hpp" ;;
    *) echo "?" ;;
  esac
}

status=0
for dir in "$root"/*/; do
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
      [ $kind = server ] && [ ! -d "$root/$other" ] && continue  # the engine's rooms
      ok=0
      for rule in $rules; do
        if [ "$rule" = "$other" ] || [ "$rule" = "$target" ]; then ok=1; fi
      done
      [ $ok = 1 ] || echo "${hit%%:*}: $room includes $target"
    done | grep . && status=1
done
exit $status
