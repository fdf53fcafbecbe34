#!/bin/sh
# make layers: the include rules of docs/architecture.md, checked on every file under src/.
# - A layer includes only its own folder and the layers below it:
#   simd < math < kernel < models, dual < plan < api < assembly, and ref (the reference) below api only.
# - A model's folder includes no other model's folder. The shared folders of models/ (common/:
#   equations two models use; interface/, build/, file/, text/: the interface and list, builds,
#   the table-file format, text and refusals) include no model's folder.
# - The reference includes nothing of the fast path: no simd/, kernel/ or vector math (src/dual/'s
#   reference also reads only its folder's constants.h). The shared
#   reference (src/ref/) reads of models/ only the plan's data (models/interface/plan.h); a model's own
#   reference (src/models/<model>/reference*) also its folder's constants.h, state.h and
#   reference.h, and nothing else of models/; no fast-path file includes a reference.
# - No file outside src/models/ branches on a model id: the model's operations do.
# Prints each break as file:line and exits 1 if there is one.
cd "$(dirname "$0")/.." || exit 2
rank() {
    case "$1" in
    simd) echo 0 ;; math) echo 1 ;; kernel) echo 2 ;; models) echo 3 ;; dual) echo 3 ;; ref) echo 4 ;; plan) echo 4 ;;
    api) echo 5 ;; assembly) echo 6 ;; *) echo -1 ;;
    esac
}
status=0
shared_folder() { case "$1" in common | interface | build | file | text) return 0 ;; esac; return 1; }
for file in $(find src -name '*.c' -o -name '*.h' | sort); do
    layer=$(echo "$file" | cut -d/ -f2)
    model=$(echo "$file" | sed -n 's|^src/models/\([^/]*\)/.*|\1|p')
    oracle=""
    case "$file" in src/models/*/reference* | src/dual/reference*) oracle=yes ;; esac
    grep -n '^#include "' "$file" | while IFS= read -r line; do
        number=${line%%:*}
        target=$(echo "$line" | sed 's/^[0-9]*:#include "\([^"]*\)".*/\1/')
        case "$target" in
        */*) ;;
        hairbsdf.h) continue ;;
        *) # the folder's own headers: a model's reference reads only its data and its reference
            why=""
            if [ -n "$oracle" ]; then
                case "$target" in constants.h | state.h | reference.h) ;; *) why="the reference includes its model's $target" ;; esac
            elif [ -n "$model" ] && [ "$target" = reference.h ]; then
                why="a fast-path file includes its model's reference"
            fi
            if [ -n "$why" ]; then
                echo "$file:$number: $why"
                echo x >> "${TMPDIR:-/tmp}/hb_layers.$$"
            fi
            continue ;;
        esac
        top=${target%%/*}
        [ "$(rank "$top")" -ge 0 ] || continue
        why=""
        if [ -n "$oracle" ]; then
            case "$target" in
            simd/* | kernel/* | math/vmath.h) why="the reference includes the fast path's $target" ;;
            models/interface/plan.h | ref/* | "models/$model/constants.h" | "models/$model/state.h" | "models/$model/reference.h") ;;
            models/*) why="the reference includes $target, a model's fast path" ;;
            esac
        elif [ "$layer" = ref ]; then
            case "$target" in
            simd/* | kernel/* | math/vmath.h) why="the reference includes the fast path's $target" ;;
            models/interface/plan.h) ;;
            models/*) why="the reference includes $target, a model's fast path (only models/interface/plan.h)" ;;
            esac
        elif [ "$top" = ref ] && [ "$layer" != api ] && [ "$layer" != plan ]; then
            why="$layer includes the reference ($target)"
        elif [ "$(rank "$top")" -gt "$(rank "$layer")" ]; then
            why="$layer includes $target, a layer above it"
        fi
        other=$(echo "$target" | sed -n 's|^models/\([^/]*\)/.*|\1|p')
        if [ -z "$why" ] && [ -n "$other" ] && ! shared_folder "$other" && [ "$other" != "$model" ]; then
            if [ -n "$model" ] && ! shared_folder "$model"; then
                why="model $model includes model $other's $target"
            elif [ "$layer" = models ]; then
                why="a shared file of models/ includes model $other's $target"
            fi
        fi
        if [ -n "$why" ]; then
            echo "$file:$number: $why"
            echo x >> "${TMPDIR:-/tmp}/hb_layers.$$"
        fi
    done
done
grep -rnE '(==|!=) *HB_MODEL_|case HB_MODEL_' src --include='*.c' --include='*.h' | grep -v '^src/models/' |
    while IFS= read -r line; do
        echo "${line%%:*}:$(echo "$line" | cut -d: -f2): branches on a model id outside src/models/"
        echo x >> "${TMPDIR:-/tmp}/hb_layers.$$"
    done
if [ -s "${TMPDIR:-/tmp}/hb_layers.$$" ]; then
    rm -f "${TMPDIR:-/tmp}/hb_layers.$$"
    echo "layers: the includes above break docs/architecture.md's rules"
    exit 1
fi
rm -f "${TMPDIR:-/tmp}/hb_layers.$$"
echo "layers: every include under src/ keeps docs/architecture.md's rules"
