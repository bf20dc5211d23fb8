!> Tests of mesh_gmsh: one box meshed by Gmsh and saved as .msh 2.2 and 4.1
!> (tests/unit/data/box_blocks.geo), small hand-written meshes, and error cases
!> written to /tmp. Usage: test_mesh_gmsh [data directory], default tests/unit/data.
program test_mesh_gmsh
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use mesh_geometry, only: hex_volume, hex_face_area, HEX_FACE_NODES
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_gmsh, only: mesh_read_gmsh
  use check, only: check_true, check_close, check_summary
  implicit none

  integer, parameter :: LINE = 72
  real(rk), parameter :: tol = 100 * epsilon(1.0_rk)
  character(len=:), allocatable :: data_dir, scratch
  type(global_mesh_t) :: mesh22, mesh41
  character(len=NAME_LEN), allocatable :: blocks22(:), blocks41(:)

  call get_data_dir(data_dir)
  scratch = scratch_prefix()

  call read_good(data_dir//'/box_blocks_v22.msh', mesh22, blocks22)
  call check_box('2.2', mesh22, blocks22)
  call read_good(data_dir//'/box_blocks_v41.msh', mesh41, blocks41)
  call check_box('4.1', mesh41, blocks41)
  call check_same(mesh22, blocks22, mesh41, blocks41)

  call test_single_hex()
  call test_errors()
  call check_summary()

contains

  !> First command-line argument, or tests/unit/data.
  subroutine get_data_dir(dir)
    character(len=:), allocatable, intent(out) :: dir
    integer :: length, stat
    call get_command_argument(1, length=length, status=stat)
    if (stat /= 0 .or. length == 0) then
      dir = 'tests/unit/data'
    else
      allocate(character(len=length) :: dir)
      call get_command_argument(1, dir)
    end if
  end subroutine get_data_dir

  !> A /tmp path prefix unique to this run.
  function scratch_prefix() result(prefix)
    character(len=:), allocatable :: prefix
    integer(i8) :: count
    character(len=24) :: text
    call system_clock(count)
    write(text, '(i0)') count
    prefix = '/tmp/impact3d_test_mesh_gmsh_'//trim(text)//'_'
  end function scratch_prefix

  !> Read a mesh that must be good; print any message.
  subroutine read_good(path, mesh, blocks)
    character(len=*), intent(in) :: path
    type(global_mesh_t), intent(inout) :: mesh
    character(len=NAME_LEN), allocatable, intent(out) :: blocks(:)
    type(status_t) :: status
    integer :: i
    call mesh_read_gmsh(path, mesh, blocks, status)
    do i = 1, min(status%count, 10)
      write(output_unit, '(a)') '  unexpected: '//trim(status%messages(i))
    end do
    call check_true(path//' reads without error', status%count == 0)
  end subroutine read_good

  !> The box [0,2] x [0,1.5] x [0,1]: 16 hexes, 45 nodes, blocks left/right, 3 face sets.
  subroutine check_box(label, mesh, blocks)
    character(len=*), intent(in) :: label
    type(global_mesh_t), intent(in) :: mesh
    character(len=NAME_LEN), intent(in) :: blocks(:)
    real(rk) :: total, volume, xmax_left, xmin_right
    logical :: positive
    integer :: z

    call check_true(label//': 45 nodes', mesh%nnode == 45)
    call check_true(label//': 16 zones', mesh%nzone == 16)
    if (mesh%nzone /= 16 .or. mesh%nnode /= 45) return
    call check_true(label//': connectivity in 1..nnode', &
        minval(mesh%connectivity) == 1 .and. maxval(mesh%connectivity) == mesh%nnode)
    total = 0.0_rk
    positive = .true.
    xmax_left = -huge(1.0_rk)
    xmin_right = huge(1.0_rk)
    do z = 1, mesh%nzone
      volume = hex_volume(mesh%coordinates(:, mesh%connectivity(:, z)))
      positive = positive .and. volume > 0.0_rk
      total = total + volume
      if (mesh%zone_block(z) == 1) then
        xmax_left = max(xmax_left, maxval(mesh%coordinates(1, mesh%connectivity(:, z))))
      else
        xmin_right = min(xmin_right, minval(mesh%coordinates(1, mesh%connectivity(:, z))))
      end if
    end do
    call check_true(label//': every zone has a positive volume', positive)
    call check_close(label//': total volume is the box volume 2 x 1.5 x 1', total, 3.0_rk, tol)
    call check_true(label//': blocks are left, right (order of tags 5, 7)', size(blocks) == 2)
    if (size(blocks) == 2) then
      call check_true(label//': block names', blocks(1) == 'left' .and. blocks(2) == 'right')
    end if
    call check_true(label//': 8 zones in block 1', count(mesh%zone_block == 1) == 8)
    call check_true(label//': 8 zones in block 2', count(mesh%zone_block == 2) == 8)
    call check_true(label//': block 1 is x <= 1, block 2 is x >= 1', &
        xmax_left <= 1.0_rk .and. xmin_right >= 1.0_rk)

    call check_true(label//': 3 face sets', mesh%nset == 3)
    if (mesh%nset /= 3) return
    call check_true(label//': sets in order of tags 1, 5, 9', mesh%set_name(1) == 'zmax' &
        .and. mesh%set_name(2) == 'xmin' .and. mesh%set_name(3) == 'middle')
    call check_set(label, mesh, 'zmax', 3, 1.0_rk, 8, 3.0_rk)
    call check_set(label, mesh, 'xmin', 1, 0.0_rk, 4, 1.5_rk)
    call check_set(label, mesh, 'middle', 1, 1.0_rk, 4, 1.5_rk)
  end subroutine check_box

  !> A face set lying in the plane x(axis) = level with nface faces of total area.
  subroutine check_set(label, mesh, name, axis, level, nface, area)
    character(len=*), intent(in) :: label, name
    type(global_mesh_t), intent(in) :: mesh
    integer, intent(in) :: axis, nface
    real(rk), intent(in) :: level, area
    integer :: s, i, z, f
    real(rk) :: total
    logical :: planar

    s = mesh%find_set(name)
    call check_true(label//': face set '//name//' exists', s > 0)
    if (s == 0) return
    call check_true(label//': face set '//name//' size', &
        mesh%set_start(s + 1) - mesh%set_start(s) == nface)
    total = 0.0_rk
    planar = .true.
    do i = mesh%set_start(s), mesh%set_start(s + 1) - 1
      z = mesh%set_zone(i)
      f = mesh%set_face(i)
      total = total + hex_face_area(mesh%coordinates(:, mesh%connectivity(:, z)), f)
      planar = planar .and. all(mesh%coordinates(axis, &
          mesh%connectivity(HEX_FACE_NODES(:, f), z)) == level)
    end do
    call check_true(label//': face set '//name//' lies in its plane', planar)
    call check_close(label//': face set '//name//' area', total, area, tol)
  end subroutine check_set

  !> Both formats give the same mesh.
  subroutine check_same(a, blocks_a, b, blocks_b)
    type(global_mesh_t), intent(in) :: a, b
    character(len=NAME_LEN), intent(in) :: blocks_a(:), blocks_b(:)
    logical :: same
    same = a%nnode == b%nnode .and. a%nzone == b%nzone .and. a%nset == b%nset &
        .and. size(blocks_a) == size(blocks_b)
    if (same) same = all(blocks_a == blocks_b) .and. all(a%coordinates == b%coordinates) &
        .and. all(a%connectivity == b%connectivity) .and. all(a%zone_block == b%zone_block) &
        .and. all(a%set_name == b%set_name) .and. all(a%set_start == b%set_start)
    if (same) same = size(a%set_zone) == size(b%set_zone)
    if (same) same = all(a%set_zone == b%set_zone) .and. all(a%set_face == b%set_face)
    call check_true('2.2 and 4.1 files give identical meshes', same)
  end subroutine check_same

  ! ---------------------------------------------------------------------------
  ! Hand-written one-hex meshes: the unit cube, node tags 10, 20, ..., 80
  ! ---------------------------------------------------------------------------

  function format_22() result(lines)
    character(len=LINE), allocatable :: lines(:)
    lines = [character(len=LINE) :: '$MeshFormat', '2.2 0 8', '$EndMeshFormat']
  end function format_22

  function names_cube() result(lines)
    character(len=LINE), allocatable :: lines(:)
    lines = [character(len=LINE) :: '$PhysicalNames', '2', '2 1 "bottom"', '3 2 "cube"', &
        '$EndPhysicalNames']
  end function names_cube

  !> Node lines "tag x y z" of the unit cube, listed in decreasing tag order,
  !> plus an unused node 99.
  function cube_nodes() result(lines)
    character(len=LINE), allocatable :: lines(:)
    lines = [character(len=LINE) :: '99 5 5 5', '80 0 1 1', '70 1 1 1', '60 1 0 1', &
        '50 0 0 1', '40 0 1 0', '30 1 1 0', '20 1 0 0', '10 0 0 0']
  end function cube_nodes

  function nodes_22() result(lines)
    character(len=LINE), allocatable :: lines(:)
    lines = [character(len=LINE) :: '$Nodes', '9', cube_nodes(), '$EndNodes']
  end function nodes_22

  function elements_22(entries) result(lines)
    character(len=*), intent(in) :: entries(:)
    character(len=LINE), allocatable :: lines(:)
    character(len=LINE) :: count
    write(count, '(i0)') size(entries)
    lines = [character(len=LINE) :: '$Elements', count, entries, '$EndElements']
  end function elements_22

  !> The cube with the bottom quad, as 2.2.
  function cube_22() result(lines)
    character(len=LINE), allocatable :: lines(:)
    lines = [format_22(), cube_22_body()]
  end function cube_22

  !> cube_22 after $MeshFormat.
  function cube_22_body() result(lines)
    character(len=LINE), allocatable :: lines(:)
    lines = [names_cube(), nodes_22(), elements_22([character(len=LINE) :: &
        '1 3 2 1 1 10 40 30 20', '2 5 2 2 1 10 20 30 40 50 60 70 80'])]
  end function cube_22_body

  !> lines(first:last).
  function take(lines, first, last) result(part)
    character(len=*), intent(in) :: lines(:)
    integer, intent(in) :: first, last
    character(len=LINE), allocatable :: part(:)
    part = lines(first:last)
  end function take

  !> The same cube as 4.1: one surface (group 1) and one volume (group 2).
  function cube_41(with_names) result(lines)
    logical, intent(in) :: with_names
    character(len=LINE), allocatable :: lines(:)
    lines = [character(len=LINE) :: '$MeshFormat', '4.1 0 8', '$EndMeshFormat']
    if (with_names) lines = [lines, names_cube()]
    lines = [character(len=LINE) :: lines, '$Entities', '0 0 1 1', &
        '1 0 0 0 1 1 0 1 1 0', '1 0 0 0 1 1 1 1 2 0', '$EndEntities', &
        '$Nodes', '1 9 10 99', '3 1 0 9', '99', '80', '70', '60', '50', '40', '30', '20', &
        '10', '5 5 5', '0 1 1', '1 1 1', '1 0 1', '0 0 1', '0 1 0', '1 1 0', '1 0 0', &
        '0 0 0', '$EndNodes', '$Elements', '2 2 1 2', '2 1 3 1', '1 10 40 30 20', &
        '3 1 5 1', '2 10 20 30 40 50 60 70 80', '$EndElements']
  end function cube_41

  subroutine write_lines(path, lines)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: lines(:)
    integer :: unit, i
    open(newunit=unit, file=path, status='replace', action='write')
    do i = 1, size(lines)
      write(unit, '(a)') trim(lines(i))
    end do
    close(unit)
  end subroutine write_lines

  subroutine delete_file(path)
    character(len=*), intent(in) :: path
    integer :: unit, ios
    open(newunit=unit, file=path, status='old', iostat=ios)
    if (ios == 0) close(unit, status='delete')
  end subroutine delete_file

  !> name with every character other than a letter or digit replaced by '_'.
  pure function file_name(name) result(text)
    character(len=*), intent(in) :: name
    character(len=len(name)) :: text
    integer :: i
    text = name
    do i = 1, len(name)
      if (verify(name(i:i),  &
          'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789') /= 0) text(i:i) = '_'
    end do
  end function file_name

  !> Write lines to a scratch file and read it back.
  subroutine read_lines(name, lines, mesh, blocks, status, path)
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: lines(:)
    type(global_mesh_t), intent(inout) :: mesh
    character(len=NAME_LEN), allocatable, intent(out) :: blocks(:)
    type(status_t), intent(out) :: status
    character(len=:), allocatable, intent(out) :: path
    path = scratch//file_name(name)//'.msh'
    call write_lines(path, lines)
    call mesh_read_gmsh(path, mesh, blocks, status)
    call delete_file(path)
  end subroutine read_lines

  !> The one-hex meshes that must read: face numbering, renumbering, fallback names.
  subroutine test_single_hex()
    type(global_mesh_t) :: mesh
    character(len=NAME_LEN), allocatable :: blocks(:)
    type(status_t) :: status
    character(len=:), allocatable :: path
    character(len=LINE), allocatable :: lines(:)
    integer :: i

    call read_lines('cube22', cube_22(), mesh, blocks, status, path)
    call check_true('cube 2.2: reads', status%count == 0)
    call check_true('cube 2.2: unused node 99 dropped', mesh%nnode == 8 .and. mesh%nzone == 1)
    if (mesh%nnode == 8 .and. mesh%nzone == 1) then
      ! Tags 10..80 in increasing order are the unit-cube corners in VTK order.
      call check_true('cube 2.2: nodes renumbered in tag order', all(mesh%coordinates == &
          reshape([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1] &
          * 1.0_rk, [3, 8])))
      call check_true('cube 2.2: connectivity', all(mesh%connectivity(:, 1) == &
          [(int(i, ik), i = 1, 8)]))
      call check_close('cube 2.2: volume', hex_volume(mesh%coordinates(:, &
          mesh%connectivity(:, 1))), 1.0_rk, tol)
      call check_true('cube 2.2: block cube', size(blocks) == 1 .and. blocks(1) == 'cube' &
          .and. mesh%zone_block(1) == 1)
      call check_true('cube 2.2: bottom quad is face 1 of zone 1', mesh%nset == 1 .and. &
          mesh%set_start(2) == 2 .and. mesh%set_zone(1) == 1 .and. mesh%set_face(1) == 1)
    end if

    ! The bottom quad listed with the opposite orientation still finds face 1.
    lines = [format_22(), names_cube(), nodes_22(), elements_22([character(len=LINE) :: &
        '1 3 2 1 1 10 20 30 40', '2 5 2 2 1 10 20 30 40 50 60 70 80'])]
    call read_lines('reversed', lines, mesh, blocks, status, path)
    call check_true('reversed quad: matches face 1', status%count == 0 .and. mesh%nset == 1)
    if (status%count == 0 .and. mesh%nset == 1) then
      call check_true('reversed quad: zone 1 face 1', mesh%set_zone(1) == 1 .and. &
          mesh%set_face(1) == 1)
    end if

    ! The top face in group 1, a line and a point in 1D/0D groups, a triangle in no group.
    lines = [format_22(), names_cube(), nodes_22(), elements_22([character(len=LINE) :: &
        '1 15 2 1 1 10', '2 1 2 1 1 10 20', '3 2 2 0 1 10 20 30', &
        '4 3 2 1 1 50 60 70 80', '5 5 2 2 1 10 20 30 40 50 60 70 80'])]
    call read_lines('ignored', lines, mesh, blocks, status, path)
    call check_true('points, lines, free triangles ignored', status%count == 0 .and. &
        mesh%nzone == 1 .and. mesh%nset == 1)
    if (status%count == 0 .and. mesh%nset == 1) then
      call check_true('top quad is face 2', mesh%set_face(1) == 2)
    end if

    ! 2.2 without $PhysicalNames: the groups are called physical_N.
    lines = [format_22(), nodes_22(), elements_22([character(len=LINE) :: &
        '1 3 2 4 1 10 40 30 20', '2 5 2 3 1 10 20 30 40 50 60 70 80'])]
    call read_lines('unnamed22', lines, mesh, blocks, status, path)
    call check_true('2.2 without names: reads', status%count == 0)
    if (status%count == 0) then
      call check_true('2.2 without names: physical_3 and physical_4', size(blocks) == 1 &
          .and. blocks(1) == 'physical_3' .and. mesh%set_name(1) == 'physical_4')
    end if

    call read_lines('cube41', cube_41(.true.), mesh, blocks, status, path)
    call check_true('cube 4.1: reads', status%count == 0)
    if (status%count == 0) then
      call check_true('cube 4.1: one hex, 8 nodes, set bottom face 1', mesh%nnode == 8 .and. &
          mesh%nzone == 1 .and. mesh%nset == 1 .and. mesh%set_face(1) == 1 .and. &
          blocks(1) == 'cube' .and. mesh%set_name(1) == 'bottom')
    end if
  end subroutine test_single_hex

  !> Read lines that must fail; the messages must name the file and contain fragment.
  subroutine expect_error(name, lines, fragment)
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: lines(:)
    character(len=*), intent(in) :: fragment
    type(global_mesh_t) :: mesh
    character(len=NAME_LEN), allocatable :: blocks(:)
    type(status_t) :: status
    character(len=:), allocatable :: path

    call read_lines(name, lines, mesh, blocks, status, path)
    call check_messages(name, path, status, fragment)
    call check_true(name//': mesh left empty', mesh%nzone == 0 .and. mesh%nnode == 0 .and. &
        size(blocks) == 0)
  end subroutine expect_error

  subroutine check_messages(name, path, status, fragment)
    character(len=*), intent(in) :: name, path, fragment
    type(status_t), intent(in) :: status
    logical :: named, found
    integer :: i
    named = status%count > 0
    found = .false.
    do i = 1, min(status%count, size(status%messages))
      write(output_unit, '(a)') '  message: '//trim(status%messages(i))
      named = named .and. index(status%messages(i), "mesh file '"//path//"': ") == 1
      found = found .or. index(status%messages(i), fragment) > 0
    end do
    call check_true(name//': error reported', status%count > 0)
    call check_true(name//': every message starts with the file name', named)
    call check_true(name//': a message says "'//fragment//'"', found)
  end subroutine check_messages

  subroutine test_errors()
    type(global_mesh_t) :: mesh
    character(len=NAME_LEN), allocatable :: blocks(:)
    type(status_t) :: status
    character(len=:), allocatable :: path

    path = scratch//'missing.msh'
    call mesh_read_gmsh(path, mesh, blocks, status)
    call check_messages('missing file', path, status, 'no such file')

    call expect_error('binary', [character(len=LINE) :: '$MeshFormat', '4.1 1 8', &
        '$EndMeshFormat', cube_22_body()], 'binary')
    call expect_error('version 3.0', [character(len=LINE) :: '$MeshFormat', '3.0 0 8', &
        '$EndMeshFormat', cube_22_body()], 'version 3.0 is not supported')
    call expect_error('not a mesh', [character(len=LINE) :: 'hello'], 'not a Gmsh mesh')
    call expect_error('truncated $Nodes', [format_22(), names_cube(), &
        take(nodes_22(), 1, 6)], 'unexpected end of file')
    call expect_error('$Nodes count too small', [format_22(), names_cube(), &
        [character(len=LINE) :: '$Nodes', '8'], cube_nodes(), &
        [character(len=LINE) :: '$EndNodes']], 'bad counts')
    call expect_error('$Elements count too large', [format_22(), names_cube(), nodes_22(), &
        [character(len=LINE) :: '$Elements', '3', '2 5 2 2 1 10 20 30 40 50 60 70 80', &
        '$EndElements']], 'expected an element tag')
    call expect_error('inverted hex', [format_22(), names_cube(), nodes_22(), &
        elements_22([character(len=LINE) :: '7 5 2 2 1 50 60 70 80 10 20 30 40'])], &
        'hexahedron 7 has volume -1.0000E+00 <= 0')
    call expect_error('quad matching no hex face', [format_22(), names_cube(), nodes_22(), &
        elements_22([character(len=LINE) :: '1 3 2 1 1 10 20 70 80', &
        '2 5 2 2 1 10 20 30 40 50 60 70 80'])], 'quadrilateral 1 of face set ''bottom'' '// &
        'matches no hexahedron face')
    call expect_error('unknown node tag', [format_22(), names_cube(), nodes_22(), &
        elements_22([character(len=LINE) :: '2 5 2 2 1 10 20 30 40 50 60 70 81'])], &
        'refers to node 81, which is not in $Nodes')
    call expect_error('tetrahedron in a 3D group', [format_22(), names_cube(), nodes_22(), &
        elements_22([character(len=LINE) :: '2 5 2 2 1 10 20 30 40 50 60 70 80', &
        '3 4 2 2 1 10 20 40 50'])], 'impact3d needs hexahedra')
    call expect_error('volume in two 3D groups', [format_22(), [character(len=LINE) :: &
        '$PhysicalNames', '2', '3 2 "cube"', '3 3 "copy"', '$EndPhysicalNames'], nodes_22(), &
        elements_22([character(len=LINE) :: '2 5 2 2 1 10 20 30 40 50 60 70 80', &
        '3 5 2 3 1 10 20 30 40 50 60 70 80'])], 'hexahedra 2 and 3 have the same nodes')
    call expect_error('hex in no group', [format_22(), names_cube(), nodes_22(), &
        elements_22([character(len=LINE) :: '2 5 2 0 1 10 20 30 40 50 60 70 80'])], &
        'is in no 3D physical group')
    call expect_error('duplicate names', [format_22(), [character(len=LINE) :: &
        '$PhysicalNames', '3', '2 1 "bottom"', '2 2 "bottom"', '3 2 "cube"', &
        '$EndPhysicalNames'], nodes_22(), elements_22([character(len=LINE) :: &
        '1 3 2 1 1 10 40 30 20', '2 3 2 2 1 50 60 70 80', &
        '3 5 2 2 1 10 20 30 40 50 60 70 80'])], 'have the same name ''bottom''')
    call expect_error('4.1 without names', cube_41(.false.), 'no $PhysicalNames section')
  end subroutine test_errors

end program test_mesh_gmsh
