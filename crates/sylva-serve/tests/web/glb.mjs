// A reader of the one thing the city test needs from a tile: its EXT_structural_metadata
// property table (scalar numbers and strings, the kinds `sylva city` writes), read straight
// from the GLB's JSON and binary chunks, apart from the page's own reader, so that the test
// checks the page against the file.

const SIZES = { FLOAT32: 4, FLOAT64: 8, UINT8: 1, UINT16: 2, UINT32: 4, INT32: 4 };

export function propertyTable(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (view.getUint32(0, true) !== 0x46546c67) throw new Error('not a GLB');
  const jsonLength = view.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength)));
  const binStart = 20 + jsonLength + 8;
  const ext = json.extensions?.EXT_structural_metadata;
  const table = ext?.propertyTables?.[0];
  if (!table) return null;
  const schema = ext.schema.classes[table.class].properties;
  const slice = (viewIndex) => {
    const bv = json.bufferViews[viewIndex];
    if (bv.buffer !== 0) throw new Error('a property table outside the GLB');
    return new DataView(bytes.buffer, bytes.byteOffset + binStart + (bv.byteOffset || 0), bv.byteLength);
  };
  return {
    count: table.count,
    get(name, i) {
      const p = table.properties[name];
      const kind = schema[name];
      if (!p || !kind) throw new Error(`no property ${name}`);
      if (kind.type === 'STRING') {
        const offsets = slice(p.stringOffsets);
        const size = SIZES[p.stringOffsetType || 'UINT32'];
        const at = (k) => (size === 4 ? offsets.getUint32(k * 4, true) : offsets.getUint16(k * 2, true));
        const values = slice(p.values);
        const raw = new Uint8Array(values.buffer, values.byteOffset + at(i), at(i + 1) - at(i));
        return new TextDecoder().decode(raw);
      }
      const values = slice(p.values);
      switch (kind.componentType) {
        case 'FLOAT32': return values.getFloat32(i * 4, true);
        case 'FLOAT64': return values.getFloat64(i * 8, true);
        case 'UINT32': return values.getUint32(i * 4, true);
        case 'INT32': return values.getInt32(i * 4, true);
        case 'UINT16': return values.getUint16(i * 2, true);
        case 'UINT8': return values.getUint8(i, true);
        default: throw new Error(`${name}: ${kind.componentType} not read here`);
      }
    },
  };
}
