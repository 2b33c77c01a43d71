#!/usr/bin/env bash
# Lints docker/Dockerfile and docker/compose.yaml without a container runtime:
# named Debian bookworm stages (build, then runtime last), the runtime stage
# runs as a non-root user with a HEALTHCHECK on /api/health, a volume for the
# database, --host 0.0.0.0 with no token or --allow-anonymous baked in, and no
# secrets (no ENV/ARG/literal holding a token, password or key). Given the
# built binary, also checks that the runtime stage installs the package of
# every shared library the binary links (ldd + dpkg -S).
# Usage: dockerfile_lint_test.sh REPO_ROOT [RRLAB_BINARY]
set -uo pipefail
root="${1:?repository root}"
binary="${2:-}"
dockerfile="$root/docker/Dockerfile"
compose="$root/docker/compose.yaml"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok   $*"; }

# instructions with continuation lines joined, comments dropped
joined=$(sed -e 's/[[:space:]]*#.*$//' "$dockerfile" | awk '/\\$/ { sub(/\\$/, ""); line = line $0; next } { print line $0; line = "" }' | grep -v '^[[:space:]]*$')
froms=$(grep -iE '^FROM ' <<<"$joined")
[[ $(wc -l <<<"$froms") -ge 2 ]] && pass "multi-stage ($(wc -l <<<"$froms") stages)" || fail "expected at least two stages"
while read -r _ image as name; do
  [[ $image == debian:bookworm* ]] || fail "stage $name: image $image is not Debian bookworm"
  [[ ${as,,} == as && -n $name ]] || fail "stage from $image has no name"
done <<<"$froms"
grep -qiE '^FROM debian:bookworm[^ ]* AS build$' <<<"$froms" && pass "a build stage" || fail "no stage named build"
last=$(tail -n 1 <<<"$froms")
[[ ${last,,} == *" as runtime" ]] && pass "the last stage is runtime" || fail "the last stage is not named runtime: $last"

# the runtime stage's instructions
runtime=$(awk 'BEGIN{IGNORECASE=1} /^FROM .* AS runtime$/ {on=1; next} /^FROM / {on=0} on' <<<"$joined")
users=$(grep -iE '^USER ' <<<"$runtime" | awk '{print $2}')
final_user=$(tail -n 1 <<<"$users")
if [[ -z $final_user ]]; then fail "the runtime stage sets no USER"
elif [[ $final_user == root || $final_user == 0 || $final_user == 0:* || $final_user == root:* ]]; then fail "the runtime runs as root"
else pass "runs as non-root user $final_user"; fi
user_line=$(grep -niE '^USER ' <<<"$runtime" | tail -n 1 | cut -d: -f1)
start_line=$(grep -niE '^(ENTRYPOINT|CMD) ' <<<"$runtime" | head -n 1 | cut -d: -f1)
[[ -n $user_line && -n $start_line && $user_line -lt $start_line ]] && pass "USER before the start command" || fail "USER must come before ENTRYPOINT/CMD"
grep -qiE '^HEALTHCHECK .*CMD .*/api/health' <<<"$runtime" && pass "HEALTHCHECK on /api/health" || fail "no HEALTHCHECK on /api/health in the runtime stage"
grep -qiE '^VOLUME .*/data' <<<"$runtime" && pass "a volume for the database" || fail "no VOLUME /data"
entry=$(grep -iE '^ENTRYPOINT ' <<<"$runtime")
[[ $entry == *'"--host", "0.0.0.0"'* ]] && pass "--host 0.0.0.0" || fail "ENTRYPOINT does not bind 0.0.0.0: $entry"
grep -q -- '--db", "/data/' <<<"$entry" && pass "database on the volume" || fail "ENTRYPOINT's --db is not under /data"
for flag in --allow-anonymous --token --public-read; do
  grep -q -- "$flag" <<<"$(grep -iE '^(ENTRYPOINT|CMD) ' <<<"$runtime")" && fail "the start command bakes in $flag"
done
for what in build/cli/rrlab web scenarios; do
  grep -qE "^COPY --from=build /src/$what " <<<"$runtime" && pass "copies $what" || fail "the runtime stage does not copy $what"
done

# no secrets: no ENV/ARG assigning a token, password, secret or key; no literal token anywhere
if grep -iE '^(ENV|ARG) ' <<<"$joined" | grep -iqE '(TOKEN|PASSW|SECRET|API_?KEY|PRIVATE)'; then
  fail "an ENV/ARG names a secret: $(grep -iE '^(ENV|ARG) ' <<<"$joined" | grep -iE '(TOKEN|PASSW|SECRET|KEY)')"
else pass "no ENV/ARG secrets"; fi
grep -qE 'RRLAB_TOKEN=[^ ]' <<<"$joined" && fail "the Dockerfile assigns RRLAB_TOKEN"
grep -qE 'BEGIN [A-Z ]*PRIVATE KEY' "$dockerfile" "$compose" && fail "a private key in the docker files"
if grep -E '^\s*RRLAB_TOKEN:' "$compose" | grep -qvE 'RRLAB_TOKEN:\s*\$\{RRLAB_TOKEN[:?}]'; then
  fail "compose.yaml sets RRLAB_TOKEN to a literal, not \${RRLAB_TOKEN...}"
else pass "compose takes the token from the environment"; fi
grep -qE '^\s*- "?127\.0\.0\.1:8080:8080' "$compose" && pass "compose publishes on loopback" || fail "compose publishes beyond 127.0.0.1"
grep -qE '^\s*- rrlab-data:/data' "$compose" && pass "compose keeps the database in a volume" || fail "no volume for /data in compose.yaml"

# the runtime packages cover the binary's shared libraries
if [[ -n $binary ]] && command -v dpkg >/dev/null; then
  install=$(grep -iE '^RUN .*apt-get install' <<<"$runtime" | head -n 1 | sed -E 's/.*apt-get install//; s/&&.*//')
  declare -A listed=([libc6]=1)  # in every Debian image
  for word in $install; do [[ $word == -* ]] || listed[$word]=1; done
  while read -r lib path; do
    [[ -z $path ]] && { fail "ldd: $lib not found"; continue; }
    package=$(dpkg -S "$(readlink -f "$path")" 2>/dev/null | head -n 1 | cut -d: -f1)
    [[ -z $package ]] && package=$(dpkg -S "$path" 2>/dev/null | head -n 1 | cut -d: -f1)
    if [[ -n ${listed[$package]:-} ]]; then pass "$lib from $package"; else fail "$lib comes from $package, which the runtime stage does not install"; fi
  done < <(ldd "$binary" | awk '/=>/ { print $1, ($3 == "not" ? "" : $3) }')
fi

if ((failures)); then echo "$failures failed"; exit 1; fi
echo "all checks passed"
