# SPDX-License-Identifier: BSD-3-Clause
# Validates the module description a Slicer CLI module prints with --xml against the Slicer Execution
# Model schema (pipelines/slicer/schema/README.md says why a corrected copy is used).
#   cmake -DMODULE=<executable> -DSCHEMA=<ModuleDescription.xsd> -DWORK_DIR=<dir> -P validate_xml.cmake
find_program(XMLLINT xmllint REQUIRED)
file(MAKE_DIRECTORY "${WORK_DIR}")
execute_process(COMMAND "${MODULE}" --xml OUTPUT_FILE "${WORK_DIR}/module.xml" RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${MODULE} --xml exited with ${code}")
endif()
file(READ "${SCHEMA}" schema)
set(misplaced "      </xsd:complexContent>\n      <xsd:attribute name=\"hidden\" type=\"xsd:boolean\"/>\n    </xsd:complexType>")
set(single "<xsd:element name=\"element\" type=\"xsd:string\"/>")
string(FIND "${schema}" "${misplaced}" at_misplaced)
string(FIND "${schema}" "${single}" at_single)
if(at_misplaced EQUAL -1 OR at_single EQUAL -1)
  message(FATAL_ERROR "the schema is not the published one the corrections were written for")
endif()
string(REPLACE "${misplaced}" "      </xsd:complexContent>\n    </xsd:complexType>" schema "${schema}")
string(REPLACE "${single}" "<xsd:element name=\"element\" type=\"xsd:string\" maxOccurs=\"unbounded\"/>" schema "${schema}")
file(WRITE "${WORK_DIR}/ModuleDescription.xsd" "${schema}")
execute_process(COMMAND "${XMLLINT}" --noout --schema "${WORK_DIR}/ModuleDescription.xsd" "${WORK_DIR}/module.xml"
                RESULT_VARIABLE code ERROR_VARIABLE errors)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the module description does not validate:\n${errors}")
endif()
message(STATUS "${errors}")
