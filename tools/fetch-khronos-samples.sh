#!/usr/bin/env bash
# Makes DEST/Models, the Khronos glTF sample models, for tools/khronos_gallery.py (issue 39):
#   tools/fetch-khronos-samples.sh DEST [GIT_DIR]
# Without GIT_DIR: a shallow clone of github.com/KhronosGroup/glTF-Sample-Assets (about 1 GB).
# With GIT_DIR (a bare repository or a mirror of it, e.g. a snapshot that left its largest files
# out): every file of HEAD's Models/ that the repository holds is written out, and the paths it
# lacks are listed in DEST/absent.txt, which the gallery reads to name the models it cannot
# render rather than count them against TRay.
set -euo pipefail
dest=${1:?usage: tools/fetch-khronos-samples.sh DEST [GIT_DIR]}
git_dir=${2:-}
mkdir -p "$dest"
if [ -z "$git_dir" ]; then
  if [ ! -d "$dest/repo" ]; then
    git clone --depth 1 https://github.com/KhronosGroup/glTF-Sample-Assets "$dest/repo"
  fi
  rm -rf "$dest/Models"
  ln -s repo/Models "$dest/Models"
  : >"$dest/absent.txt"
  exit 0
fi
: >"$dest/absent.txt"
written=0
while IFS=$'\t' read -r -d '' meta path; do
  read -r _ _ sha <<<"$meta"
  if git --git-dir="$git_dir" cat-file -e "$sha" 2>/dev/null; then
    mkdir -p "$dest/$(dirname "$path")"
    git --git-dir="$git_dir" cat-file blob "$sha" >"$dest/$path"
    written=$((written + 1))
  else
    echo "$path" >>"$dest/absent.txt"
  fi
done < <(git --git-dir="$git_dir" ls-tree -r -z HEAD Models)  # -z: names unquoted (Unicode❤♻Test)
echo "fetch-khronos-samples: $written files in $dest/Models, $(wc -l <"$dest/absent.txt") absent" \
  "(listed in $dest/absent.txt)"
