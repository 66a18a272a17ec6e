// The report's 3-D view: a WebGL canvas drawn by three.js (Debian's libjs-three, r111), inlined so
// the page stays one self-contained file. The bodies travel as JSON in a script element that the
// viewer script (below, our own) turns into meshes: orbit and zoom with the mouse (three.js's
// OrbitControls when the package ships it, else a small handler of our own), click a body to see
// its key, volume and azimuth.

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "geotandem/workflow/report.hpp"

namespace geotandem::workflow {
namespace {

// GEOTANDEM_THREE_JS_DIR overrides the Debian location (a directory laid out like it).
std::string three_dir() {
  const char* dir = std::getenv("GEOTANDEM_THREE_JS_DIR");
  return dir && *dir ? dir : "/usr/share/javascript/three";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// Script text safe inside <script>: a literal "</script" would end the element early.
std::string script_safe(std::string text) {
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 2))
    text.replace(at, 2, "<\\/");
  return text;
}

std::string fixed(double v, int precision) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", precision, v);
  return text;
}

std::string bodies_json(const ReportSurvey& survey, const std::vector<ReportBody>& bodies,
                        const std::string& volume_unit) {
  const auto& origin = survey.corners[0];
  std::ostringstream j;
  // Vertical exaggeration, as report_views.cpp clustered with.
  const double z_scale = display_z_scale(survey);
  j << "{\"z_unit\":\"" << survey.z_unit << "\",\"z_min\":" << fixed(survey.z_min, 3)
    << ",\"z_max\":" << fixed(survey.z_max, 3) << ",\"z_scale\":" << fixed(z_scale, 6) << ",\"origin\":["
    << fixed(origin[0], 2) << "," << fixed(origin[1], 2) << "],\"volume_unit\":\"" << volume_unit
    << "\",\"triangle_budget\":" << kDisplayTriangleBudget << ",\"corners\":[";
  for (std::size_t c = 0; c < 4; ++c)
    j << (c ? "," : "") << "[" << fixed(survey.corners[c][0] - origin[0], 2) << ","
      << fixed(survey.corners[c][1] - origin[1], 2) << "]";
  j << "],\"bodies\":[";
  for (std::size_t n = 0; n < bodies.size(); ++n) {
    const ReportBody& b = bodies[n];
    j << (n ? "," : "") << "{\"key\":" << b.key << ",\"volume\":" << std::setprecision(6) << b.volume
      << ",\"azimuth\":" << fixed(b.azimuth, 2) << ",\"closed\":" << (b.closed ? "true" : "false") << ",\"colour\":\""
      << azimuth_colour(b.azimuth) << "\",\"full_triangles\":" << b.full_triangles << ",\"points\":[";
    for (std::size_t v = 0; v < b.points.size(); ++v)
      j << (v ? "," : "") << fixed(b.points[v][0], 1) << "," << fixed(b.points[v][1], 1) << ","
        << fixed(b.points[v][2], 2);
    j << "],\"triangles\":[";
    for (std::size_t t = 0; t < b.triangles.size(); ++t)
      j << (t ? "," : "") << b.triangles[t][0] << "," << b.triangles[t][1] << "," << b.triangles[t][2];
    j << "]}";
  }
  j << "]}";
  return j.str();
}

// The viewer: our own code. World (east, north, z down) maps to three.js's (x, y up, z toward
// the viewer) as (east, -(z - z_min) * z_scale, -north), which keeps the frame right-handed.
const char* viewer_script = R"JS(
(function () {
  var info = document.getElementById('gt-info');
  var canvas = document.getElementById('gt-view');
  var data = JSON.parse(document.getElementById('geotandem-bodies').textContent);
  if (typeof THREE === 'undefined') { info.textContent = 'three.js did not load: no 3-D view.'; return; }
  var renderer;
  try {
    renderer = new THREE.WebGLRenderer({canvas: canvas, antialias: true, preserveDrawingBuffer: true});
  } catch (e) { info.textContent = 'This browser gives no WebGL context: no 3-D view (' + e.message + ').'; return; }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(canvas.clientWidth, canvas.clientHeight, false);
  var scene = new THREE.Scene();
  scene.background = new THREE.Color(0xfafafa);
  var zs = data.z_scale;
  function at(x, y, z) { return new THREE.Vector3(x, -(z - data.z_min) * zs, -y); }
  function attribute(g, name, a) { if (g.setAttribute) g.setAttribute(name, a); else g.addAttribute(name, a); }

  // The survey: its outline at the first and last sample, and the vertical edges.
  var c = data.corners, edges = [];
  for (var n = 0; n < 4; n++) {
    var p = c[n], q = c[(n + 1) % 4];
    [data.z_min, data.z_max].forEach(function (z) { edges.push(at(p[0], p[1], z), at(q[0], q[1], z)); });
    edges.push(at(p[0], p[1], data.z_min), at(p[0], p[1], data.z_max));
  }
  var box = new THREE.BufferGeometry().setFromPoints(edges);
  scene.add(new THREE.LineSegments(box, new THREE.LineBasicMaterial({color: 0x888888})));
  box.computeBoundingSphere();
  var sphere = box.boundingSphere;
  var length = sphere.radius * 0.35;
  var north = new THREE.ArrowHelper(new THREE.Vector3(0, 0, -1), at(c[0][0], c[0][1], data.z_min), length, 0x222222,
                                    length * 0.3, length * 0.15);
  scene.add(north);

  var meshes = [];
  data.bodies.forEach(function (b) {
    if (!b.triangles.length) return;
    var pos = new Float32Array(b.points.length);
    for (var i = 0; i < b.points.length; i += 3) {
      var v = at(b.points[i], b.points[i + 1], b.points[i + 2]);
      pos[i] = v.x; pos[i + 1] = v.y; pos[i + 2] = v.z;
    }
    var g = new THREE.BufferGeometry();
    attribute(g, 'position', new THREE.BufferAttribute(pos, 3));
    g.setIndex(b.triangles);
    g.computeVertexNormals();
    var m = new THREE.Mesh(g, new THREE.MeshPhongMaterial({color: b.colour, side: THREE.DoubleSide,
                                                           flatShading: true, shininess: 15}));
    m.userData = b;
    scene.add(m);
    meshes.push(m);
  });

  var camera = new THREE.PerspectiveCamera(40, canvas.clientWidth / canvas.clientHeight,
                                           sphere.radius / 100, sphere.radius * 20);
  camera.position.copy(sphere.center).add(new THREE.Vector3(0.9, 0.8, 1.3).multiplyScalar(sphere.radius * 1.5));
  camera.lookAt(sphere.center);
  scene.add(new THREE.AmbientLight(0xffffff, 0.45));
  var light = new THREE.DirectionalLight(0xffffff, 0.75);
  light.position.set(0.3, 1, 0.6);
  camera.add(light);
  scene.add(camera);

  function render() { renderer.render(scene, camera); }
  var controls;
  if (THREE.OrbitControls) {
    controls = new THREE.OrbitControls(camera, canvas);
    controls.target.copy(sphere.center);
    controls.update();
    controls.addEventListener('change', render);
  } else {
    // A small orbit and zoom handler: drag turns the camera around the centre, the wheel zooms.
    var offset = camera.position.clone().sub(sphere.center), drag = null;
    var spherical = new THREE.Spherical().setFromVector3(offset);
    var place = function () {
      camera.position.copy(sphere.center).add(new THREE.Vector3().setFromSpherical(spherical));
      camera.lookAt(sphere.center); render();
    };
    canvas.addEventListener('pointerdown', function (e) { drag = [e.clientX, e.clientY]; });
    window.addEventListener('pointerup', function () { drag = null; });
    canvas.addEventListener('pointermove', function (e) {
      if (!drag) return;
      spherical.theta -= (e.clientX - drag[0]) * 0.01;
      spherical.phi = Math.min(Math.PI - 0.05, Math.max(0.05, spherical.phi - (e.clientY - drag[1]) * 0.01));
      drag = [e.clientX, e.clientY]; place();
    });
    canvas.addEventListener('wheel', function (e) {
      e.preventDefault(); spherical.radius *= e.deltaY > 0 ? 1.1 : 1 / 1.1; place();
    }, {passive: false});
  }

  // Click (not drag) a body: its key, volume and azimuth.
  var down = null, chosen = null, ray = new THREE.Raycaster();
  canvas.addEventListener('pointerdown', function (e) { down = [e.clientX, e.clientY]; });
  canvas.addEventListener('click', function (e) {
    if (down && Math.abs(e.clientX - down[0]) + Math.abs(e.clientY - down[1]) > 4) return;
    var r = canvas.getBoundingClientRect();
    ray.setFromCamera(new THREE.Vector2((e.clientX - r.left) / r.width * 2 - 1,
                                        -(e.clientY - r.top) / r.height * 2 + 1), camera);
    var hit = ray.intersectObjects(meshes)[0];
    if (chosen) chosen.material.emissive.setHex(0x000000);
    chosen = hit ? hit.object : null;
    if (chosen) {
      chosen.material.emissive.setHex(0x3a3a3a);
      var b = chosen.userData;
      info.innerHTML = 'body <b>' + b.key + '</b> &middot; volume ' +
        (b.closed ? b.volume.toPrecision(4) + ' ' + data.volume_unit : '&ndash; (cut by the border)') +
        ' &middot; azimuth ' + b.azimuth.toFixed(1) + '&deg; &middot; ' + (b.triangles.length / 3) +
        ' of ' + b.full_triangles + ' triangles shown';
    } else {
      info.textContent = 'Click a body to see its key, volume and azimuth.';
    }
    render();
  });
  render();
  canvas.setAttribute('data-drawn', meshes.length);
})();
)JS";

} // namespace

std::string body_viewer_html(const ReportSurvey& survey, const std::vector<ReportBody>& bodies,
                             const std::string& volume_unit) {
  const std::string dir = three_dir();
  const std::string three = read_text(dir + "/build/three.min.js");
  const std::string orbit = read_text(dir + "/examples/js/controls/OrbitControls.js");
  std::ostringstream h;
  if (three.empty()) {
    h << "<p class=\"meta\">No 3-D view: three.js was not found in <code>" << dir
      << "/build/three.min.js</code>. Install Debian's <code>libjs-three</code> (scripts/setup.sh does), or point "
         "GEOTANDEM_THREE_JS_DIR at a copy, and run the workflow again.</p>";
    return h.str();
  }
  h << "<div class=\"viewer\"><canvas id=\"gt-view\" width=\"640\" height=\"480\"></canvas><div id=\"gt-info\" "
       "class=\"meta\">Click a body to see its key, volume and azimuth.</div></div>\n";
  h << "<script type=\"application/json\" id=\"geotandem-bodies\">"
    << script_safe(bodies_json(survey, bodies, volume_unit)) << "</script>\n";
  h << "<script>/* three.js r111 (MIT licence), from Debian's libjs-three */\n"
    << script_safe(three) << "\n</script>\n";
  if (!orbit.empty()) h << "<script>\n" << script_safe(orbit) << "\n</script>\n";
  h << "<script>" << viewer_script << "</script>\n";
  return h.str();
}

} // namespace geotandem::workflow
