#!/usr/bin/env bash
# js/test.sh: builds the npm package (one Emscripten build) and tests it.
# Prints `ok   <name>`, `FAIL <name>` (details indented) and `SKIP <name>: why`
# lines, then "N passed, N failed"; exits non-zero when anything failed.
#
# Installs what is missing when it can (root with apt-get): Debian's nodejs
# and npm, emscripten, assimp-testmodels, chromium (the page's test); the npm
# dev dependencies go into js/node_modules (npm ci). Without node or emcc it
# says SKIP and passes; without chromium, when not root, it skips the page's
# browser test the same way.
# Build outputs: js/dist (the package's files), js/build (test scratch).
set -u
cd "$(dirname "$0")"
js=$(pwd)
logs=build/logs
mkdir -p "$logs"
passed=0
failed=0
models=${MESHFIX_GLTF_MODELS:-/usr/share/assimp/models/glTF2}

ok() { passed=$((passed + 1)); echo "ok   $1"; }
fail() { # name, log file
    failed=$((failed + 1))
    echo "FAIL $1"
    [ -n "${2:-}" ] && [ -f "$2" ] && sed 's/^/    /' "$2" | tail -n 20
}
finish() {
    echo "$passed passed, $failed failed"
    [ "$failed" -eq 0 ]
    exit
}
step() { # name, command...: ok or FAIL with the command's output (kept in $last_log)
    local name=$1
    last_log="$logs/$(echo "$name" | tr -c 'A-Za-z0-9' _).log"
    shift
    if "$@" >"$last_log" 2>&1; then ok "$name"; return 0; else fail "$name" "$last_log"; return 1; fi
}
suite() { # name, command...: a node test printing its own ok/FAIL lines
    local name=$1 log status
    log="$logs/$(echo "$name" | tr -c 'A-Za-z0-9' _).log"
    shift
    "$@" >"$log" 2>&1
    status=$?
    grep -E '^(ok   |FAIL |SKIP |    )' "$log"
    passed=$((passed + $(grep -c '^ok   ' "$log")))
    failed=$((failed + $(grep -c '^FAIL ' "$log")))
    if [ "$status" -ne 0 ] && ! grep -q '^FAIL ' "$log"; then
        fail "$name: exit status $status" "$log"
    fi
}
apt_install() { # packages...: installs them when we are root with apt-get
    [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1 || return 1
    echo "installing: $*"
    export DEBIAN_FRONTEND=noninteractive
    { apt-get update -qq && apt-get install -y -qq "$@"; } >"$logs/apt.log" 2>&1
}

echo "== npm package (js/): WebAssembly build, API, glTF-Transform transform"

# tools
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    need=()
    command -v node >/dev/null 2>&1 || need+=(nodejs)
    command -v npm >/dev/null 2>&1 || need+=(npm)
    apt_install "${need[@]}"
fi
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    echo "SKIP js: node and npm are not installed and could not be (apt-get install nodejs npm)"
    finish
fi
if ! command -v emcc >/dev/null 2>&1; then
    apt_install emscripten
fi
if ! command -v emcc >/dev/null 2>&1; then
    echo "SKIP js: emcc is not installed and could not be (apt-get install emscripten)"
    finish
fi
if [ ! -d "$models" ] && [ -z "${MESHFIX_GLTF_MODELS:-}" ]; then
    apt_install assimp-testmodels
fi
echo "node $(node --version), npm $(npm --version), $(emcc --version 2>/dev/null | head -n 1)"

# dev dependencies (@gltf-transform/core, gltf-validator, typescript, puppeteer-core) into js/node_modules
step "npm ci: dev dependencies into js/node_modules" npm ci --no-audit --no-fund || finish

# the one Emscripten build: dist/meshfix.mjs and dist/meshfix.cjs
step "build: meshfix.h with emcc into dist/meshfix.mjs and dist/meshfix.cjs (WebAssembly inlined)" \
    node scripts/build.mjs || finish
step "build: dist/ has no reference to a .wasm file or a URL to fetch" \
    sh -c '! grep -E "\.wasm[\"'\'']|fetch\(|https?://" dist/meshfix.mjs dist/meshfix.cjs'

# the native reference build of the same header
native=build/native_orient
step "build: test/native_orient.c, the native reference" \
    sh -c "${CC:-cc} -std=c99 -O2 -Wall -Wextra -I.. test/native_orient.c -o $native -lm" || native=

suite "API" node test/api.test.mjs $native
suite "transform on built documents" node test/transform.test.mjs $native
if [ -d "$models" ]; then
    suite "transform on assimp-testmodels" node test/models.test.mjs "$native" "$models"
else
    echo "SKIP glTF models: $models is missing (Debian: apt-get install assimp-testmodels)"
fi
step "TypeScript: meshfix.d.ts compiles a user's code (tsc --strict)" npx tsc -p test/tsconfig.json

# the browser page (page/): built into build/page; its readers and writers
# under node, then the page itself in Debian's Chromium, headless, through
# puppeteer-core; both compare what they write with the command-line tool's
# output (../build/meshfix, built here when missing)
cli=../build/meshfix
if [ ! -x "$cli" ]; then
    step "build: ../build/meshfix, the command-line tool the page is compared with" make -C .. -s build/meshfix || cli=
fi
if step "page: scripts/page.mjs builds page/ into build/page (meshfix.mjs, glTF-Transform vendored)" \
    node scripts/page.mjs build/page; then
    if [ -n "$cli" ]; then
        suite "page: readers and writers" node test/page_files.test.mjs build/page "$cli" "$(dirname "$models")"
    fi
    chromium=$(command -v chromium || true)
    if [ -z "$chromium" ]; then
        apt_install chromium
        chromium=$(command -v chromium || true)
    fi
    engine="$models/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
    if [ -z "$chromium" ] && [ "$(id -u)" -ne 0 ]; then
        echo "SKIP the page in Chromium: chromium is not installed and only root can install it (apt-get install chromium)"
    elif [ -z "$chromium" ]; then
        failed=$((failed + 1))
        echo "FAIL the page in Chromium: apt-get install chromium failed (see $logs/apt.log)"
    elif [ -z "$cli" ] || [ ! -f "$engine" ]; then
        failed=$((failed + 1))
        echo "FAIL the page in Chromium: needs ../build/meshfix and $engine (apt-get install assimp-testmodels)"
    else
        suite "page in Chromium" node test/page.test.mjs "$chromium" build/page "$cli" "$engine" "$(dirname "$models")"
    fi
fi

# npm pack, then a new project installs the tarball and uses it
pack=$(mktemp -d)
trap 'rm -rf "$pack"' EXIT
if step "npm pack (prepack reuses this run's build)" sh -c "npm pack --pack-destination '$pack' >'$pack/name'"; then
    tarball="$pack/$(tail -n 1 "$pack/name")"
    step "npm pack: the tarball holds dist/, the types, README and LICENSE, and is small" sh -c "
        tar -tzf '$tarball' | sort >'$pack/files' && cat '$pack/files' &&
        grep -qx package/dist/meshfix.mjs '$pack/files' && grep -qx package/dist/meshfix.cjs '$pack/files' &&
        grep -qx package/meshfix.d.ts '$pack/files' && grep -qx package/README.md '$pack/files' &&
        grep -qx package/LICENSE '$pack/files' && [ \$(wc -l <'$pack/files') -le 7 ] &&
        [ \$(stat -c %s '$tarball') -lt 400000 ]"
    core=$(node -p "require('./node_modules/@gltf-transform/core/package.json').version")
    mkdir -p "$pack/app"
    cp test/consumer/orient.cjs test/consumer/gltf.mjs "$pack/app/"
    if step "a new project installs the tarball (and @gltf-transform/core $core)" sh -c "
        cd '$pack/app' && npm init -y >/dev/null &&
        npm install --no-audit --no-fund --prefer-offline '$tarball' '@gltf-transform/core@$core'"; then
        step "the new project: require('meshfix-wasm') orients a mesh" sh -c "cd '$pack/app' && node orient.cjs"
        model="$models/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
        if [ -f "$model" ]; then
            if step "the new project: import { meshfix } repairs scrambled 2CylinderEngine.glb" \
                sh -c "cd '$pack/app' && node gltf.mjs '$model' out.glb report.json"; then
                sed 's/^/    /' "$last_log"
                if [ -n "$native" ]; then
                    step "the new project's output: glTF-Validator 0 errors, flips as the native build" \
                        node test/consumer/verify.mjs "$native" "$pack/app/out.glb" "$pack/app/report.json" &&
                        sed 's/^/    /' "$last_log"
                fi
            fi
        else
            echo "SKIP the new project's glTF check: $model is missing"
        fi
    fi
fi

finish
