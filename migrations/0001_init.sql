-- Initial schema of reenact-server. Applied once, inside a transaction, by the migration
-- runner (server/storage/migrations.h); the schema version is PRAGMA user_version.

-- People who may upload. A token is stored only as the hex SHA-256 of its text.
CREATE TABLE users (
  id         INTEGER PRIMARY KEY,
  name       TEXT NOT NULL UNIQUE,
  created_at INTEGER NOT NULL                -- unix seconds
);

CREATE TABLE tokens (
  id           INTEGER PRIMARY KEY,
  user_id      INTEGER NOT NULL REFERENCES users(id) ON DELETE CASCADE,
  token_sha256 TEXT NOT NULL UNIQUE,         -- 64 lowercase hex digits
  created_at   INTEGER NOT NULL
);

-- One row per clip; a draft until every part has arrived and publish succeeded.
CREATE TABLE clips (
  rowid_key       INTEGER PRIMARY KEY,       -- internal key, shared with clip_boxes.id
  public_id       TEXT NOT NULL UNIQUE,      -- opaque id handed to clients
  owner_id        INTEGER NOT NULL REFERENCES users(id),
  state           TEXT NOT NULL CHECK (state IN ('draft', 'published')),
  title           TEXT NOT NULL,
  author          TEXT NOT NULL,
  lat_deg         REAL NOT NULL CHECK (lat_deg BETWEEN -90 AND 90),
  lon_deg         REAL NOT NULL CHECK (lon_deg BETWEEN -180 AND 180),
  alt_m           REAL NOT NULL,
  duration_s      REAL NOT NULL,
  frame_count     INTEGER NOT NULL CHECK (frame_count >= 0),
  manifest        BLOB NOT NULL,             -- the manifest JSON exactly as uploaded
  manifest_sha256 TEXT NOT NULL,
  created_at      INTEGER NOT NULL,
  published_at    INTEGER
);
CREATE INDEX clips_by_owner ON clips(owner_id);
CREATE INDEX clips_by_state ON clips(state);

-- Every part the manifest promises: frames (part_index >= 0) and the map (part_index = -1).
CREATE TABLE clip_parts (
  clip_key   INTEGER NOT NULL REFERENCES clips(rowid_key) ON DELETE CASCADE,
  part_index INTEGER NOT NULL CHECK (part_index >= -1),
  bytes      INTEGER NOT NULL CHECK (bytes >= 0),
  sha256     TEXT NOT NULL,
  present    INTEGER NOT NULL DEFAULT 0 CHECK (present IN (0, 1)),
  PRIMARY KEY (clip_key, part_index)
) WITHOUT ROWID;

-- Spatial pre-filter: one degenerate box (a point) per clip, in degrees. The R*Tree stores
-- 32-bit floats rounded outwards, so it only pre-filters; exact distances decide.
CREATE VIRTUAL TABLE clip_boxes USING rtree(id, min_lat, max_lat, min_lon, max_lon);

CREATE TRIGGER clips_drop_box AFTER DELETE ON clips BEGIN
  DELETE FROM clip_boxes WHERE id = old.rowid_key;
END;

-- Default blob store: frame and map payloads keyed by "<clip id>/frames/<n>" or "<clip id>/map".
CREATE TABLE blobs (
  key  TEXT PRIMARY KEY,
  data BLOB NOT NULL
);
