// three.js r111 for the viewer's modules. The page loads Debian's three.min.js and
// examples/js/controls/OrbitControls.js as classic scripts before the modules run
// (src/view/viewer_page.h): they define the global THREE, which this module alone reads.
export const THREE = window.THREE;
if (!THREE || !THREE.OrbitControls) throw new Error('three.js r111 and its OrbitControls did not load before the viewer');
