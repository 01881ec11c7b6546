#!/usr/bin/env bash
# What the tests need besides the build (scripts/setup-deps.sh): Debian's Chromium, Node.js with npm
# and playwright-core from the npm registry (tests/web/package-lock.json) for the browser tests,
# clang-format for the style check, and nginx for the test of docker/nginx.conf in front of two
# server replicas (it runs its own nginx; the package's service is not used).
# Idempotent: installs only what is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
missing=()
dpkg-query -W -f='${Status}' chromium 2>/dev/null | grep -q "install ok installed" || missing+=(chromium)
command -v clang-format >/dev/null || missing+=(clang-format)  # test style.ClangFormat
# Node.js by command, not package: a Node.js from elsewhere (NodeSource bundles npm) conflicts
# with Debian's npm package, and any Node.js >= 18 with npm will do.
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)
# nginx in front of two server replicas (RedisReplicas.NginxKeepsABrowserOnOneReplica, docker/nginx.conf).
command -v nginx >/dev/null || [ -x /usr/sbin/nginx ] || missing+=(nginx-light)
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup-test-deps: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
if [ ! -d tests/web/node_modules/playwright-core ]; then
  echo "setup-test-deps: npm ci in tests/web"
  npm ci --prefix tests/web --no-audit --no-fund --loglevel=error
fi
