"""Text files written by other tools (part programs, trace exports): their bytes as text.

Windows tools write UTF-8 with or without a byte-order mark, UTF-16 (with its mark; some without), or the
Windows code page (Windows-1252, e.g. the "Ø" and "°" of a comment). The rule, for every reader:

- a byte-order mark picks UTF-8 or UTF-16 (the mark is not part of the text);
- without one, NUL bytes mean UTF-16 when every second byte of the start is NUL (little- or big-endian text
  of the ASCII range), else binary data, refused (:class:`BinaryDataError`);
- otherwise UTF-8, or Windows-1252 when the bytes are not valid UTF-8 (undefined bytes become U+FFFD).
"""

from __future__ import annotations

__all__ = ["BinaryDataError", "decode_text", "ZIP_SIGNATURE"]

#: How a ZIP archive begins: the signature of its first local file header, 0x04034b50 little-endian (PKWARE's
#: APPNOTE.TXT 4.3.7). FMUs, NumPy's ``.npz`` and Office Open XML workbooks are ZIP archives: binary, never text.
ZIP_SIGNATURE = b"PK\x03\x04"

_BOMS = ((b"\xef\xbb\xbf", "utf-8-sig"), (b"\xff\xfe", "utf-16"), (b"\xfe\xff", "utf-16"))
_PROBE = 4096  # bytes looked at for UTF-16 without a mark


class BinaryDataError(ValueError):
    """The bytes are no text (the readers turn this into their own error naming the file).

    Attributes
    ----------
    line, column : int
        Where the first offending byte is (1-based; the line counted by LF bytes, the column in bytes).
    """

    def __init__(self, message: str, raw: bytes, offset: int) -> None:
        super().__init__(message)
        self.line = raw.count(b"\n", 0, offset) + 1
        self.column = offset - (raw.rfind(b"\n", 0, offset) + 1) + 1


def decode_text(raw: bytes) -> str:
    """``raw`` as text by the module's rule.

    Raises
    ------
    BinaryDataError
        NUL bytes without a UTF-16 byte-order mark or pattern, or bytes that are not valid after their mark.
    """
    for bom, codec in _BOMS:
        if raw.startswith(bom):
            try:
                return raw.decode(codec)
            except UnicodeDecodeError as exc:
                raise BinaryDataError(f"not valid {codec} text after its byte-order mark (byte {exc.start})",
                                      raw, exc.start) from None
    if b"\x00" in raw:
        head = raw[: min(len(raw), _PROBE) // 2 * 2]
        for codec, nul in (("utf-16-le", head[1::2]), ("utf-16-be", head[0::2])):
            if head and len(raw) % 2 == 0 and nul.count(0) == len(nul):
                try:
                    return raw.decode(codec)
                except UnicodeDecodeError:
                    break
        raise BinaryDataError("binary file (NUL bytes and no UTF-16 byte-order mark)", raw, raw.index(b"\x00"))
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        return raw.decode("cp1252", errors="replace")
