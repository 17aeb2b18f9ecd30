// The page's data (the JSON that `contactlab view` or the live view put in the page,
// src/view/view_data.h), the options in the address's fragment, and the job selector of a
// results folder of several jobs.
import { el } from './util.js';

// Options in the address's fragment: #job=I, #t=SECONDS, #model=NAME, #play (joined with &),
// and #bench=orbit[&frames=N] (orbit_bench.js).
export function readOptions() {
  const options = {};
  location.hash.replace(/^#/, '').split('&').forEach(function (kv) {
    if (!kv) return;
    const parts = kv.split('=');
    options[decodeURIComponent(parts[0])] = parts.length > 1 ? decodeURIComponent(parts[1]) : '';
  });
  return options;
}

// X with every {"$blob": N} replaced by BLOBS[N].
function resolveBlobs(x, blobs) {
  if (Array.isArray(x)) return x.map(function (item) { return resolveBlobs(item, blobs); });
  if (x === null || typeof x !== 'object') return x;
  const keys = Object.keys(x);
  if (keys.length === 1 && keys[0] === '$blob') return blobs[x.$blob];
  const out = {};
  keys.forEach(function (k) { out[k] = resolveBlobs(x[k], blobs); });
  return out;
}

// A job's label as its option shows it: each value of a path (a scene file, a mesh) by its
// file's name alone, each key path by its last key ("scene=scenes/block-joint.yaml
// scene.bodies[name=tool].mesh=meshes/peg.obj" -> "scene=block-joint mesh=peg").
export function shortLabel(label) {
  return label.split(' ').map(function (pair) {
    const at = pair.indexOf('=', Math.max(0, pair.indexOf(']')));  // past a selector's own '=' ([name=tool])
    if (at < 0) return pair;
    const key = pair.slice(0, at).replace(/^.*\]\./, '').replace(/^.*\./, '');
    const value = pair.slice(at + 1).replace(/^.*\//, '').replace(/\.(yaml|yml|obj|off|stl|ply)(\.gz)?$/, '');
    return key + '=' + value;
  }).join(' ');
}

// The selector of PAGEDATA's jobs, JOBINDEX chosen: choosing another reloads the page at #job=I.
function showJobSelector(pageData, jobIndex) {
  const jobSelect = document.getElementById('job');
  pageData.jobs.forEach(function (j) {
    jobSelect.appendChild(el('option', {value: String(j.job)}, 'job ' + j.job + (j.label ? ': ' + shortLabel(j.label) : '')));
  });
  jobSelect.value = String(pageData.jobs[jobIndex].job);
  // The chosen job's whole label, wrapped under the selector (an option cannot wrap).
  document.getElementById('job-label').textContent = pageData.jobs[jobIndex].label || '';
  jobSelect.addEventListener('change', function () {
    location.hash = 'job=' + encodeURIComponent(jobSelect.value);
    location.reload();
  });
  document.getElementById('job-choice').hidden = false;
  document.documentElement.setAttribute('data-jobs', String(pageData.jobs.length));
}

// The data to show. A results folder of several jobs (view_data.h, SeveralJobsViewData) holds
// every job's data, their long strings in shared "blobs": the page shows the job of #job=I
// (the first when absent or not among them) and a selector that reloads it with another.
export function loadPageData(options) {
  const pageData = JSON.parse(document.getElementById('contactlab-data').textContent);
  let data = pageData;
  if (pageData.job_data) {
    let jobIndex = 0;
    pageData.jobs.forEach(function (j, i) { if (String(j.job) === options.job) jobIndex = i; });
    data = resolveBlobs(pageData.job_data[jobIndex], pageData.blobs);
    showJobSelector(pageData, jobIndex);
  }
  if (data.replay) document.documentElement.setAttribute('data-job', String(data.replay.job));
  return data;
}
