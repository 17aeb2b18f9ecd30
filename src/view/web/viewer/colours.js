// The viewer's colours. Each family keeps clear of the others' hues so a screenshot can tell
// them apart (tests/view/check_page.py): body A orange, body B blue, levels neither.
export const BODY_COLOURS = [0xe8862a, 0x2f6fd0];
// A scene of many bodies: the tool orange, the others in shades of blue (and grey-blue), so a
// screenshot still tells the tool from the rest.
const OTHER_BODY_COLOURS = [0x2f6fd0, 0x5b8fe6, 0x1f4a96, 0x7f9fc8, 0x3c5e88, 0x8ab4f0];
// The colour of body I of SPECS (the page data's "bodies").
export function bodyColour(specs, i) {
  if (specs.length <= 2 && !specs.some(function (b) { return b.tool; })) return BODY_COLOURS[i];
  if (specs[i].tool) return BODY_COLOURS[0];
  let others = 0;  // the index of body I among the bodies that are not the tool
  for (let k = 0; k < i; ++k) if (!specs[k].tool) ++others;
  return OTHER_BODY_COLOURS[others % OTHER_BODY_COLOURS.length];
}
// Pointshell levels; red is kept for points in contact.
export const LEVEL_COLOURS = ['#ffe14d', '#3cc83c', '#d040d0', '#40e0e0', '#a0ff60', '#9060ff',
                              '#f0f0f0', '#ff80c0', '#00a080', '#c0c000', '#b0b0ff', '#808080'];
export const CONTACT_COLOUR = '#ff1010';
// Live contact marks: evaluated points sky blue (clear of body B's hue), the rest dim grey.
export const EVALUATED_COLOUR = '#38c8ff';
export const UNEVALUATED_COLOUR = '#5a5e64';
export const FORCE_COLOUR = 0xff3030;
// Contact surfaces (pressure-field), by pressure: dark teal (0) through green to pale yellow
// (the largest), hues clear of the bodies' and the contact red.
export const PRESSURE_STOPS = [[0, 80, 70], [120, 200, 60], [255, 240, 120]];
// Force plot tracks, one per model of a replay in the order of its model selector: the current
// one is drawn thicker; hues clear of the bodies' orange and blue and of the contact red.
export const TRACK_COLOURS = ['#ffd000', '#50d890', '#d080ff', '#ff80c0', '#a0f040', '#40e0d0', '#f0f0f0',
                              '#c0a0ff', '#e0e070', '#80ffb0'];
