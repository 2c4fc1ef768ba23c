"""Defects found in the review of session 27's trace readers (review27), each with a file written here."""

from __future__ import annotations

import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError

_STREAMS = """<?xml version="1.0" encoding="{encoding}"?>
<m:MTConnectStreams xmlns:m="urn:mtconnect.org:MTConnectStreams:2.0"><m:Header creationTime="2021-01-01T00:00:00Z"/>
<m:Streams><m:DeviceStream name="mill" uuid="mill"><m:ComponentStream component="Linear" name="X"><m:Samples>
<m:Position dataItemId="Xact" timestamp="2021-01-01T00:00:00.1Z" name="Xact" subType="ACTUAL">1.0</m:Position>
<m:Position dataItemId="Xcmd" timestamp="2021-01-01T00:00:00.1Z" subType="COMMANDED">1.0</m:Position>
</m:Samples></m:ComponentStream></m:DeviceStream></m:Streams></m:MTConnectStreams>
"""


@pytest.mark.parametrize("encoding, bom", [("UTF-8", "utf-8"), ("UTF-16", "utf-16")])
def test_mtconnect_samples_with_a_namespace_prefix_are_named(tmp_path, encoding, bom):
    # prefixed samples (<m:Position>) and a UTF-16 file were named "its position samples: none; no COMMANDED
    # position among them" although the document holds both
    f = tmp_path / "sample.xml"
    f.write_text(_STREAMS.format(encoding=encoding), encoding=bom)
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    msg = str(err.value)
    assert "its position samples: Xact (ACTUAL) x1, Xcmd (COMMANDED) x1. vcnc identifies" in msg


@pytest.mark.parametrize("root, what", [("MTConnectDevices", "devices document (an agent's /probe answer"),
                                        ("m:MTConnectError", "error document (an agent's answer to a request it")])
def test_an_mtconnect_probe_or_error_document_is_named(tmp_path, root, what):
    # an agent's /probe answer was refused as "an XML file with root <MTConnectDevices>, not a SINUMERIK trace"
    f = tmp_path / "probe.xml"
    f.write_text(f'<?xml version="1.0"?>\n<{root} xmlns:m="urn:mtconnect.org:{root[-7:]}:1.3"><Header/></{root}>\n')
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert str(err.value).startswith(f"{f}: an MTConnect {what}")
    assert "SINUMERIK trace (<traceSession>" not in str(err.value)
