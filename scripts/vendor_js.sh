#!/bin/sh
# Reproduce urdf_lint/preview/static/vendor/: three.js, its loaders and OrbitControls and
# gkjohnson's urdf-loader, bundled by esbuild into ONE classic script (vendor.js) that sets
# window.URDFV. A classic script, not ES modules: the review page of `urdf-lint diff --html`
# opens from file://, where Chromium refuses module scripts. Run from the repository root;
# needs node and npm (the npm registry), nothing else. The versions are pinned here and
# written to VERSIONS.txt beside the bundle, with each package's LICENSE.
set -eu
THREE=0.187.0
URDF_LOADER=0.13.1
ESBUILD=0.28.2
out="$(pwd)/urdf_lint/preview/static/vendor"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
npm init -y >/dev/null
npm install --no-audit --no-fund --silent "three@$THREE" "urdf-loader@$URDF_LOADER" \
    "esbuild@$ESBUILD"
cat > entry.js <<'JS'
import { Scene, PerspectiveCamera, WebGLRenderer, Color, AmbientLight, DirectionalLight,
         HemisphereLight, GridHelper, AxesHelper, Group, Mesh, MeshBasicMaterial,
         MeshPhongMaterial, SphereGeometry, Box3, Vector3, Vector2, Raycaster, LoadingManager,
         Object3D, BufferGeometry, Float32BufferAttribute, LineSegments, LineBasicMaterial,
         EdgesGeometry, DoubleSide, SRGBColorSpace, Quaternion, Euler, Matrix4,
         TextureLoader, MathUtils } from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import { ColladaLoader } from 'three/examples/jsm/loaders/ColladaLoader.js';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { MTLLoader } from 'three/examples/jsm/loaders/MTLLoader.js';
import URDFLoader from 'urdf-loader/src/URDFLoader.js';
window.URDFV = { Scene, PerspectiveCamera, WebGLRenderer, Color, AmbientLight,
  DirectionalLight, HemisphereLight, GridHelper, AxesHelper, Group, Mesh, MeshBasicMaterial,
  MeshPhongMaterial, SphereGeometry, Box3, Vector3, Vector2, Raycaster, LoadingManager,
  Object3D, BufferGeometry, Float32BufferAttribute, LineSegments, LineBasicMaterial,
  EdgesGeometry, DoubleSide, SRGBColorSpace, Quaternion, Euler, Matrix4, TextureLoader,
  MathUtils, OrbitControls, STLLoader, ColladaLoader, OBJLoader, MTLLoader, URDFLoader };
JS
mkdir -p "$out"
./node_modules/.bin/esbuild entry.js --bundle --minify --format=iife --target=es2020 \
    --legal-comments=none --outfile="$out/vendor.js"
cp node_modules/three/LICENSE "$out/LICENSE.three.txt"
# the npm package ships no LICENSE file: its package.json says Apache-2.0, and the
# repository (gkjohnson/urdf-loaders) holds the plain Apache-2.0 text with this notice
{
    echo "urdf-loader (https://github.com/gkjohnson/urdf-loaders), Apache-2.0."
    echo "Copyright 2019 California Institute of Technology"
    echo
    cat /usr/share/common-licenses/Apache-2.0
} > "$out/LICENSE.urdf-loader.txt"
{
    echo "vendor.js: one esbuild bundle (scripts/vendor_js.sh) of"
    echo "three $THREE (MIT, LICENSE.three.txt): core, OrbitControls, STL/Collada/OBJ/MTL loaders"
    echo "urdf-loader $URDF_LOADER (Apache-2.0, LICENSE.urdf-loader.txt), by Garrett Johnson"
    echo "bundled with esbuild $ESBUILD"
} > "$out/VERSIONS.txt"
ls -l "$out"
